#include "bench/output/html_report.hpp"

#include <optional>
#include <utility>
#include <vector>

#include "bench/output/internal/report_page.hpp"
#include "io/atomic_file.hpp"
#include "io/markup_escape.hpp"

namespace retrace::bench {

namespace fs = std::filesystem;

namespace {

const char* const kCss = R"(
body{font:14px/1.45 system-ui,-apple-system,"Segoe UI",sans-serif;margin:0;color:#222;background:#fafafa}
header{background:#263238;color:#fff;padding:14px 24px}
header h1{margin:0 0 4px;font-size:22px}
header p{margin:2px 0;color:#cfd8dc}
header code{background:#37474f;color:#fff}
nav{margin-top:8px}
nav a{color:#80deea;margin-right:14px;text-decoration:none}
main{padding:4px 24px 40px}
section{margin:18px 0;padding:10px 16px;background:#fff;border:1px solid #e0e0e0;border-radius:4px}
h2{margin:4px 0 10px;font-size:19px}
h3{font-size:16px;margin:14px 0 6px}
h4,h5,h6{font-size:14px;margin:10px 0 4px}
table{border-collapse:collapse;font-size:13px;margin:6px 0}
th,td{border:1px solid #cfd8dc;padding:3px 8px;vertical-align:top}
th{background:#eceff1;text-align:left}
td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
tr.fail td{background:#fdecea;color:#b71c1c;font-weight:600}
tr.improved td{background:#e8f5e9}
.fail-text{color:#b71c1c;font-weight:700}
.pass-text{color:#1b5e20;font-weight:700}
.scroll{overflow-x:auto;max-width:100%}
figure{display:inline-block;vertical-align:top;margin:8px 12px 12px 0;max-width:100%}
figure img{display:block;max-width:100%;height:auto;border:1px solid #ddd;background:#fff}
figcaption{font-size:12px;color:#455a64;margin-top:4px;max-width:900px}
pre{background:#f5f5f5;padding:8px;overflow-x:auto;font-size:12px;max-height:480px}
code{background:#f1f1f1;padding:0 3px}
details{margin:6px 0}
summary{cursor:pointer;color:#37474f}
.note{color:#607d8b}
)";

// Sets data-images="<decoded>/<total>" on the body once every image has loaded or failed.
const char* const kScript = R"(
window.addEventListener('load', function () {
  var images = document.images, decoded = 0;
  for (var i = 0; i < images.length; ++i) {
    if (images[i].complete && images[i].naturalWidth > 0) ++decoded;
  }
  document.body.dataset.images = decoded + '/' + images.length;
});
)";

}  // namespace

std::string HtmlEscape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (const char* entity = io::MarkupEntity(c)) {
      out += entity;
    } else {
      out += c;
    }
  }
  return out;
}

HtmlReport BuildHtmlReport(const fs::path& dir) {
  const report::Folder folder = report::Walk(dir);
  const auto [kind, description] = report::Kind(folder);
  HtmlReport page;
  page.kind = kind;

  std::vector<report::Section> sections;
  auto add = [&](std::optional<report::Section> s) {
    if (s) sections.push_back(std::move(*s));
  };
  add(report::SuiteSection(folder));
  add(report::SummarySection(folder));
  add(report::ComparisonSection(folder));
  add(report::SweepSection(folder));
  sections.push_back(report::FiguresSection(folder, &page.images));
  add(report::ProvenanceSection(folder));
  sections.push_back(report::FilesSection(folder, kind == "folder"));

  fs::path shown = dir;
  if (shown.filename().empty()) shown = shown.parent_path();  // "results/x/"
  const std::string name = HtmlEscape(fs::absolute(shown).lexically_normal().filename().string());
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; "
      "style-src 'unsafe-inline'; script-src 'unsafe-inline'\">\n"
      "<title>retrace report: " +
      name + "</title>\n<style>" + kCss + "</style>\n</head>\n<body>\n<header>\n<h1>" + name +
      "</h1>\n<p>" + HtmlEscape(description) + "</p>\n<p><code>" + HtmlEscape(shown.string()) +
      "</code>, " + std::to_string(folder.files.size()) + " files, " + std::to_string(page.images) +
      " figures</p>\n<nav>";
  for (const report::Section& s : sections) html += "<a href=\"#" + s.id + "\">" + s.title + "</a>";
  html += "</nav>\n</header>\n<main>\n";
  for (const report::Section& s : sections) {
    html += "<section id=\"" + s.id + "\">\n<h2>" + s.title + "</h2>\n" + s.html + "</section>\n";
  }
  html += "</main>\n<script>" + std::string(kScript) + "</script>\n</body>\n</html>\n";
  page.html = std::move(html);
  return page;
}

HtmlReport WriteHtmlReport(const fs::path& dir) {
  HtmlReport page = BuildHtmlReport(dir);
  io::WriteFileAtomic(dir / "report.html", page.html);
  return page;
}

}  // namespace retrace::bench
