#include <cmath>
#include <cstdio>

#include "bench/output/html_report.hpp"
#include "bench/output/internal/report_page.hpp"
#include "core/format.hpp"
#include "io/json_writer.hpp"

namespace retrace::bench::report {

namespace fs = std::filesystem;
using nlohmann::json;

std::string Number(double v) {
  if (!std::isfinite(v)) return "n/a";
  return core::Printf("%.4g", v);
}

std::string SignedNumber(double v) {
  if (!std::isfinite(v)) return "n/a";
  return core::Printf("%+.4g", v);
}

bool IsScalar(const json& v) { return !v.is_object() && !v.is_array(); }

// A JSON value as cell text (not yet escaped).
std::string Text(const json& v) {
  if (v.is_null()) return "n/a";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return std::to_string(v.get<std::int64_t>());
  if (v.is_number_unsigned()) return std::to_string(v.get<std::uint64_t>());
  if (v.is_number()) return Number(v.get<double>());
  if (v.is_string()) return v.get<std::string>();
  if (v.is_array()) {
    std::string text;
    for (const json& e : v) text += (text.empty() ? "" : ", ") + Text(e);
    return "[" + text + "]";
  }
  return v.dump();
}

std::string Cell(const json& v) {
  const std::string cls = v.is_number() || v.is_null() ? " class=\"num\"" : "";
  return "<td" + cls + ">" + HtmlEscape(Text(v)) + "</td>";
}

// Dotted names of every scalar (and short list of scalars) in `v`.
void Flatten(const json& v, const std::string& prefix, std::map<std::string, json>* out) {
  if (v.is_object()) {
    for (const auto& [key, value] : v.items())
      Flatten(value, prefix.empty() ? key : prefix + "." + key, out);
  } else if (v.is_array()) {
    if (v.size() <= 8 && std::all_of(v.begin(), v.end(), IsScalar)) (*out)[prefix] = v;
  } else {
    (*out)[prefix] = v;
  }
}

const json* Find(const json& root, std::string_view dotted) {
  const json* node = &root;
  while (!dotted.empty()) {
    const std::size_t dot = dotted.find('.');
    const std::string key(dotted.substr(0, dot));
    if (!node->is_object() || !node->contains(key)) return nullptr;
    node = &(*node)[key];
    dotted = dot == std::string_view::npos ? std::string_view{} : dotted.substr(dot + 1);
  }
  return node;
}

std::string Generic(const fs::path& rel) { return rel.generic_string(); }

json ReadJson(const fs::path& dir, const fs::path& rel) { return io::ReadJsonFile(dir / rel); }

// A two-column table of facts (already escaped values).
std::string FactsTable(const std::vector<std::pair<std::string, std::string>>& facts) {
  std::string html = "<table>\n";
  for (const auto& [key, value] : facts)
    html += "<tr><th>" + HtmlEscape(key) + "</th><td>" + value + "</td></tr>\n";
  return html + "</table>\n";
}

}  // namespace retrace::bench::report
