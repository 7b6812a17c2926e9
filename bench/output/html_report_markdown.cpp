#include "bench/output/html_report_markdown.hpp"

#include <algorithm>
#include <vector>

#include "bench/output/html_report.hpp"

namespace retrace::bench {
namespace {
// Named, so that a unity build's other files' helpers (Trim, ...) cannot clash.
namespace markdown {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

// `code` and **bold** inside a line; the rest escaped. An unmatched marker stays as text.
std::string Inline(std::string_view text) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == '`') {
      const std::size_t end = text.find('`', i + 1);
      if (end != std::string_view::npos) {
        out += "<code>" + HtmlEscape(text.substr(i + 1, end - i - 1)) + "</code>";
        i = end + 1;
        continue;
      }
    } else if (text.substr(i, 2) == "**") {
      const std::size_t end = text.find("**", i + 2);
      if (end != std::string_view::npos && end > i + 2) {
        out += "<strong>" + Inline(text.substr(i + 2, end - i - 2)) + "</strong>";
        i = end + 2;
        continue;
      }
    }
    const std::size_t next = std::min(text.find('`', i + 1), text.find("**", i + 1));
    const std::size_t stop = next == std::string_view::npos ? text.size() : next;
    out += HtmlEscape(text.substr(i, stop - i));
    i = stop;
  }
  return out;
}

// The cells of a `| a | b |` line; `\|` is a pipe inside a cell.
std::vector<std::string> TableCells(std::string_view line) {
  line = Trim(line);
  if (line.starts_with('|')) line.remove_prefix(1);
  if (line.ends_with('|') && !line.ends_with("\\|")) line.remove_suffix(1);
  std::vector<std::string> cells;
  std::string cell;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
      cell += '|';
      ++i;
    } else if (line[i] == '|') {
      cells.emplace_back(Trim(cell));
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  cells.emplace_back(Trim(cell));
  return cells;
}

bool IsSeparatorRow(const std::vector<std::string>& cells) {
  return std::all_of(cells.begin(), cells.end(), [](const std::string& c) {
    return !c.empty() && c.find('-') != std::string::npos &&
           c.find_first_not_of(":- ") == std::string::npos;
  });
}

std::string Table(const std::vector<std::string_view>& lines) {
  std::vector<std::vector<std::string>> rows;
  for (std::string_view line : lines) rows.push_back(TableCells(line));
  std::vector<std::string> align;
  std::size_t body = 1;
  if (rows.size() >= 2 && IsSeparatorRow(rows[1])) {
    for (const std::string& c : rows[1]) {
      const bool left = c.front() == ':', right = c.back() == ':';
      align.push_back(left && right ? "center" : right ? "right" : left ? "left" : "");
    }
    body = 2;
  }
  auto row_html = [&](const std::vector<std::string>& cells, const char* tag) {
    std::string html = "<tr>";
    for (std::size_t i = 0; i < cells.size(); ++i) {
      html += '<';
      html += tag;
      if (i < align.size() && !align[i].empty()) html += " style=\"text-align:" + align[i] + "\"";
      html += '>';
      html += Inline(cells[i]);
      html += "</";
      html += tag;
      html += '>';
    }
    return html + "</tr>\n";
  };
  std::string html =
      "<div class=\"scroll\"><table>\n<thead>" + row_html(rows[0], "th") + "</thead>\n<tbody>\n";
  for (std::size_t r = body; r < rows.size(); ++r) html += row_html(rows[r], "td");
  return html + "</tbody></table></div>\n";
}

}  // namespace markdown
}  // namespace

std::string MarkdownToHtml(std::string_view markdown, int heading_shift) {
  std::vector<std::string_view> lines;
  for (std::size_t start = 0; start <= markdown.size();) {
    std::size_t end = markdown.find('\n', start);
    if (end == std::string_view::npos) end = markdown.size();
    lines.push_back(markdown.substr(start, end - start));
    start = end + 1;
  }
  std::string html;
  std::string paragraph;
  auto flush_paragraph = [&] {
    if (!paragraph.empty()) html += "<p>" + paragraph + "</p>\n";
    paragraph.clear();
  };
  for (std::size_t i = 0; i < lines.size();) {
    const std::string_view line = markdown::Trim(lines[i]);
    if (line.empty()) {
      flush_paragraph();
      ++i;
    } else if (line.starts_with("```")) {
      flush_paragraph();
      std::string code;
      for (++i; i < lines.size() && !markdown::Trim(lines[i]).starts_with("```"); ++i)
        code += HtmlEscape(lines[i]) + "\n";
      html += "<pre>" + code + "</pre>\n";
      ++i;
    } else if (line.starts_with('#')) {
      flush_paragraph();
      const std::size_t level = std::min<std::size_t>(line.find_first_not_of('#'), 6);
      const int shifted = std::min(6, static_cast<int>(level) + heading_shift);
      const std::string tag = "h" + std::to_string(shifted);
      html += "<" + tag + ">" + markdown::Inline(markdown::Trim(line.substr(level))) + "</" + tag +
              ">\n";
      ++i;
    } else if (line.starts_with('|')) {
      flush_paragraph();
      std::vector<std::string_view> table;
      for (; i < lines.size() && markdown::Trim(lines[i]).starts_with('|'); ++i)
        table.push_back(lines[i]);
      html += markdown::Table(table);
    } else if (line.starts_with("- ") || line.starts_with("* ")) {
      flush_paragraph();
      html += "<ul>\n";
      for (; i < lines.size(); ++i) {
        const std::string_view item = markdown::Trim(lines[i]);
        if (!item.starts_with("- ") && !item.starts_with("* ")) break;
        html += "<li>" + markdown::Inline(markdown::Trim(item.substr(2))) + "</li>\n";
      }
      html += "</ul>\n";
    } else {
      paragraph += (paragraph.empty() ? "" : "\n") + markdown::Inline(line);
      ++i;
    }
  }
  flush_paragraph();
  return html;
}

}  // namespace retrace::bench
