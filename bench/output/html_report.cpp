#include "bench/output/html_report.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <system_error>
#include <utility>
#include <vector>

#include "bench/output/base64.hpp"
#include "bench/output/html_report_markdown.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_reader.hpp"
#include "io/json_writer.hpp"
#include "io/read_file.hpp"

namespace retrace::bench {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
// Named, so that a unity build's other files' helpers (Cell, Number, ...) cannot clash.
namespace page {

// Folders beyond this many entries are listed only in part; a results folder holds a few
// thousand files at most.
constexpr std::size_t kMaxWalkedFiles = 100000;
constexpr std::size_t kListedFiles = 500;
// A PNG larger than this is listed, not embedded: the page must stay loadable.
constexpr std::uintmax_t kMaxImageBytes = 64u << 20;

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

std::string Number(double v) {
  if (!std::isfinite(v)) return "n/a";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

std::string SignedNumber(double v) {
  if (!std::isfinite(v)) return "n/a";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%+.4g", v);
  return buffer;
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

// --- What the folder holds ------------------------------------------------------------------

struct Folder {
  fs::path dir;
  std::vector<fs::path> files;  ///< relative, sorted
  bool truncated = false;
  bool Has(const fs::path& rel) const {
    return std::binary_search(files.begin(), files.end(), rel);
  }
  std::vector<fs::path> Named(const std::string& name) const {
    std::vector<fs::path> found;
    for (const fs::path& f : files)
      if (f.filename() == name) found.push_back(f);
    return found;
  }
};

Folder Walk(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status status = fs::status(dir, ec);
  if (!fs::exists(status)) throw core::IoError(dir.string() + ": no such folder");
  if (!fs::is_directory(status)) throw core::IoError(dir.string() + ": not a folder");
  Folder folder;
  folder.dir = dir;
  fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
  if (ec) throw core::IoError(dir.string() + ": cannot read the folder: " + ec.message());
  for (; it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    const fs::path name = it->path().filename();
    const std::string ext = name.extension().string();
    if (it->is_directory(ec)) {
      // Staging folders of a command still writing (or killed): not results.
      if (ext == ".tmp" || ext == ".old") it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file(ec)) continue;
    // The page itself: a report made again must not list its previous version.
    if (it.depth() == 0 && name == "report.html") continue;
    if (folder.files.size() == kMaxWalkedFiles) {
      folder.truncated = true;
      break;
    }
    folder.files.push_back(it->path().lexically_relative(dir));
  }
  std::sort(folder.files.begin(), folder.files.end());
  return folder;
}

// --- The page's sections --------------------------------------------------------------------

struct Section {
  std::string id;
  std::string title;
  std::string html;
};

// A two-column table of facts (already escaped values).
std::string FactsTable(const std::vector<std::pair<std::string, std::string>>& facts) {
  std::string html = "<table>\n";
  for (const auto& [key, value] : facts)
    html += "<tr><th>" + HtmlEscape(key) + "</th><td>" + value + "</td></tr>\n";
  return html + "</table>\n";
}

int ModeOrder(const std::string& name) {
  static const std::vector<std::string> kOrder = {"partial", "single", "consistent",
                                                  "scan_matched"};
  const auto it = std::find(kOrder.begin(), kOrder.end(), name);
  return static_cast<int>(it - kOrder.begin());
}

struct MetricsColumn {
  std::string label;
  fs::path file;
  json values;  ///< the aggregate (run) or the whole file (log-localize)
};

struct Headline {
  const char* label;
  std::vector<const char*> keys;  ///< the first present one is shown
};

// The rows of the summary table, where a folder's metrics have them: a run's aggregates, then a
// log-localize run's.
const std::vector<Headline>& Headlines() {
  static const std::vector<Headline> kRows = {
      {"maps", {"maps"}},
      {"scans", {"scans"}},
      {"tracking error RMS (m)", {"tracking_error_m.pooled.rms"}},
      {"tracking error max (m)", {"tracking_error_m.pooled.max"}},
      {"localization error RMS (m)",
       {"localization_error_m.pooled.rms", "localization_error_m.rms"}},
      {"localization error p95 (m)",
       {"localization_error_m.pooled.p95", "localization_error_m.p95"}},
      {"localization error RMS on the route (m)", {"localization_error_on_route_m.rms"}},
      {"on the route (fraction)", {"on_route_fraction"}},
      {"repeatability (m)", {"repeatability_m"}},
      {"lost (fraction)", {"lost_fraction.pooled", "lost_fraction"}},
      {"map-switch error max (m)", {"switch_error.max_m"}},
      {"pedestrian incidents", {"collisions.pedestrian_incidents"}},
      {"static collisions", {"collisions.static_incidents"}},
      {"time in personal zone per run (s)", {"social.personal_time_s"}},
      {"min time to collision (s)", {"social.min_ttc_s"}},
      {"path efficiency", {"social.path_efficiency"}},
      {"jerk RMS (m/s³)", {"social.jerk_m_s3.rms"}},
      {"pedestrians blocked by the robot", {"social.crowd.blocked"}},
      {"beams rejected as dynamic (fraction)",
       {"dynamic_points.rejected_fraction", "rejected_fraction"}},
      {"localizer update mean (ms)", {"cpu.localizer_update_mean_ms", "update_time_ms.mean"}},
      {"real-time factor", {"cpu.real_time_factor", "real_time_factor"}},
  };
  return kRows;
}

std::optional<Section> SummarySection(const Folder& folder) {
  std::vector<MetricsColumn> columns;
  for (const fs::path& rel : folder.Named("metrics.json")) {
    const json j = ReadJson(folder.dir, rel);
    if (!j.is_object()) throw core::IoError((folder.dir / rel).string() + ": not a JSON object");
    MetricsColumn column;
    column.file = rel;
    const fs::path parent = rel.parent_path();
    column.label = j.contains("mode") && j["mode"].is_string() ? j["mode"].get<std::string>()
                   : parent.empty()                            ? std::string("this folder")
                                                               : Generic(parent);
    if (j.contains("aggregate") && j["aggregate"].is_object()) {
      column.values = j["aggregate"];
    } else {
      column.values = j;
      column.values.erase("runs");
    }
    columns.push_back(std::move(column));
  }
  if (columns.empty()) return std::nullopt;
  std::stable_sort(columns.begin(), columns.end(), [](const auto& a, const auto& b) {
    return ModeOrder(a.label) < ModeOrder(b.label);
  });

  std::string head = "<tr><th>metric</th>";
  for (const MetricsColumn& c : columns)
    head += "<th title=\"" + HtmlEscape(Generic(c.file)) + "\">" + HtmlEscape(c.label) + "</th>";
  head += "</tr>\n";

  std::string rows;
  auto row = [&](const std::string& label, auto&& value_of) {
    std::string cells;
    bool any = false;
    for (const MetricsColumn& c : columns) {
      const std::optional<json> v = value_of(c.values);
      any = any || v.has_value();
      cells += v ? Cell(*v) : "<td class=\"num\">-</td>";
    }
    if (any) rows += "<tr><th>" + HtmlEscape(label) + "</th>" + cells + "</tr>\n";
  };
  row("success", [](const json& v) -> std::optional<json> {
    const json* s = Find(v, "successes");
    const json* n = Find(v, "runs");
    if (s == nullptr || n == nullptr || !n->is_number()) return std::nullopt;
    return json(Text(*s) + "/" + Text(*n));
  });
  row("outcomes", [](const json& v) -> std::optional<json> {
    const json* o = Find(v, "outcomes");
    if (o == nullptr || !o->is_object()) return std::nullopt;
    std::string text;
    for (const auto& [outcome, count] : o->items()) {
      if (count.is_number() && count.get<double>() != 0)
        text += (text.empty() ? "" : ", ") + outcome + " " + Text(count);
    }
    return json(text.empty() ? "none" : text);
  });
  for (const Headline& h : Headlines()) {
    row(h.label, [&](const json& v) -> std::optional<json> {
      for (const char* key : h.keys)
        if (const json* found = Find(v, key); found != nullptr && IsScalar(*found)) return *found;
      return std::nullopt;
    });
  }

  std::vector<std::map<std::string, json>> flat(columns.size());
  std::vector<std::string> names;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    Flatten(columns[i].values, "", &flat[i]);
    for (const auto& [name, value] : flat[i]) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  std::string all;
  for (const std::string& name : names) {
    all += "<tr><th>" + HtmlEscape(name) + "</th>";
    for (const auto& values : flat) {
      const auto it = values.find(name);
      all += it == values.end() ? "<td class=\"num\">-</td>" : Cell(it->second);
    }
    all += "</tr>\n";
  }

  Section s{"summary", "Summary", ""};
  std::string files;
  for (const MetricsColumn& c : columns)
    files += (files.empty() ? "" : ", ") + ("<code>" + HtmlEscape(Generic(c.file)) + "</code>");
  s.html = "<p class=\"note\">From " + files +
           (columns.front().values.contains("runs") ? "; pooled over each mode's runs." : ".") +
           "</p>\n<div class=\"scroll\"><table>\n" + head + rows +
           "</table></div>\n<details><summary>All " + std::to_string(names.size()) +
           " metrics</summary>\n<div class=\"scroll\"><table>\n" + head + all +
           "</table></div>\n</details>\n";
  return s;
}

std::optional<Section> SuiteSection(const Folder& folder) {
  if (!folder.Has("report.json")) {
    if (!folder.Has("report.md")) return std::nullopt;
    return Section{"suite", "Regression suite",
                   MarkdownToHtml(io::ReadFileBytes(folder.dir / "report.md"))};
  }
  const json j = ReadJson(folder.dir, "report.json");
  if (!j.is_object() || !j.contains("rows") || !j["rows"].is_array()) return std::nullopt;
  const std::string verdict = j.contains("verdict") ? Text(j["verdict"]) : "?";
  const bool failed = verdict == "FAIL";
  Section s{"suite", "Regression suite", ""};
  s.html = "<p>Suite <strong>" + HtmlEscape(j.contains("suite") ? Text(j["suite"]) : "?") +
           "</strong>: <span class=\"" + (failed ? "fail-text" : "pass-text") + "\">" +
           HtmlEscape(verdict) + "</span>";
  if (const json* counts = Find(j, "counts"); counts != nullptr && counts->is_object()) {
    std::string parts;
    for (const auto& [key, value] : counts->items())
      parts += (parts.empty() ? "" : ", ") + HtmlEscape(key) + " " + HtmlEscape(Text(value));
    s.html += " (" + parts + ")";
  }
  if (const json* b = Find(j, "baseline"); b != nullptr && b->is_object()) {
    s.html += "; baseline <code>" + HtmlEscape(b->contains("file") ? Text((*b)["file"]) : "?") +
              "</code>";
    if (b->contains("git_revision")) s.html += ", git " + HtmlEscape(Text((*b)["git_revision"]));
    if (b->contains("date")) s.html += ", " + HtmlEscape(Text((*b)["date"]));
  }
  s.html += "</p>\n";

  auto value = [](const json& row, const char* key) {
    return row.contains(key) ? row[key] : json(nullptr);
  };
  auto numbers = [&](const json& row) {
    const json delta = value(row, "delta");
    return "<td class=\"num\">" + HtmlEscape(Text(value(row, "baseline"))) +
           "</td><td class=\"num\">" + HtmlEscape(Text(value(row, "now"))) +
           "</td><td class=\"num\">" +
           HtmlEscape(delta.is_number() ? SignedNumber(delta.get<double>()) : Text(delta)) +
           "</td>";
  };
  std::string regressions, all;
  int failures = 0;
  for (const json& row : j["rows"]) {
    if (!row.is_object()) continue;
    const std::string v = Text(value(row, "verdict"));
    const std::string name = HtmlEscape(Text(value(row, "metric")));
    const std::string tolerance = HtmlEscape(Text(value(row, "tolerance")));
    if (v == "FAIL") {
      ++failures;
      regressions += "<tr class=\"fail\"><td>" + name + "</td>" + numbers(row) + "<td>" +
                     tolerance + "</td><td>" + HtmlEscape(Text(value(row, "reason"))) +
                     "</td></tr>\n";
    }
    const std::string cls = v == "FAIL"       ? " class=\"fail\""
                            : v == "improved" ? " class=\"improved\""
                                              : "";
    all += "<tr" + cls + "><td>" + name + "</td>" + numbers(row) + Cell(value(row, "seed_sd")) +
           "<td>" + HtmlEscape(v) + "</td><td>" + tolerance + "</td><td><code>" +
           HtmlEscape(Text(value(row, "pattern"))) + "</code></td></tr>\n";
  }
  s.html += "<h3>Regressions</h3>\n";
  if (failures == 0) {
    s.html += "<p class=\"pass-text\">None: every gated metric is within its tolerance.</p>\n";
  } else {
    s.html +=
        "<div class=\"scroll\"><table>\n<tr><th>metric</th><th>baseline</th><th>now</th>"
        "<th>delta</th><th>tolerance</th><th>why</th></tr>\n" +
        regressions + "</table></div>\n";
  }
  s.html +=
      "<h3>Every metric</h3>\n<div class=\"scroll\"><table>\n<tr><th>metric</th>"
      "<th>baseline</th><th>now</th><th>delta</th><th>seed sd</th><th>verdict</th>"
      "<th>tolerance</th><th>pattern</th></tr>\n" +
      all + "</table></div>\n";
  return s;
}

// comparison.json of `retrace compare` (it has a confidence), as a table, for a folder that has
// no comparison.md.
std::string ComparisonJsonTable(const json& j) {
  const json* metrics = Find(j, "metrics");
  const json* modes = Find(j, "modes");
  if (metrics == nullptr || modes == nullptr || !metrics->is_array() || !modes->is_object())
    return "<p class=\"note\">comparison.json holds no metrics.</p>\n";
  const std::string reference = j.contains("reference") ? Text(j["reference"]) : "";
  std::string html = "<div class=\"scroll\"><table>\n<tr><th>metric</th><th>unit</th>";
  for (const auto& [mode, values] : modes->items()) html += "<th>" + HtmlEscape(mode) + "</th>";
  for (const auto& [mode, values] : modes->items()) {
    if (mode != reference) html += "<th>" + HtmlEscape(mode + " − " + reference) + "</th>";
  }
  html += "</tr>\n";
  auto interval = [](const json* v) -> std::string {
    if (v == nullptr || !v->is_object()) return "n/a";
    std::string text = v->contains("mean") ? Text((*v)["mean"]) : "n/a";
    if (const json* ci = Find(*v, "ci95"); ci != nullptr && ci->is_array() && ci->size() == 2)
      text += " [" + Text((*ci)[0]) + ", " + Text((*ci)[1]) + "]";
    if (const json* sig = Find(*v, "significant"); sig != nullptr && sig->is_boolean() && *sig)
      text += " *";
    return text;
  };
  for (const json& metric : *metrics) {
    const std::string key = metric.contains("key") ? Text(metric["key"]) : "";
    html += "<tr><th>" + HtmlEscape(metric.contains("label") ? Text(metric["label"]) : key) +
            "</th><td>" + HtmlEscape(metric.contains("unit") ? Text(metric["unit"]) : "") + "</td>";
    for (const auto& [mode, values] : modes->items()) {
      const json* v = values.contains(key) ? &values[key] : nullptr;
      html += "<td class=\"num\">" + HtmlEscape(interval(v)) + "</td>";
    }
    for (const auto& [mode, values] : modes->items()) {
      if (mode == reference) continue;
      const json* v = values.contains(key) ? Find(values[key], "vs_reference") : nullptr;
      html += "<td class=\"num\">" + HtmlEscape(interval(v)) + "</td>";
    }
    html += "</tr>\n";
  }
  return html + "</table></div>\n<p class=\"note\">Mean over seeds [95 % confidence interval]; " +
         "*: the paired difference's interval excludes 0.</p>\n";
}

std::optional<Section> ComparisonSection(const Folder& folder) {
  if (folder.Has("comparison.md")) {
    return Section{"comparison", "Comparison",
                   MarkdownToHtml(io::ReadFileBytes(folder.dir / "comparison.md"))};
  }
  if (!folder.Has("comparison.json")) return std::nullopt;
  const json j = ReadJson(folder.dir, "comparison.json");
  if (!j.is_object() || !j.contains("confidence")) return std::nullopt;  // a run's: see Summary
  return Section{"comparison", "Comparison", ComparisonJsonTable(j)};
}

std::optional<Section> SweepSection(const Folder& folder) {
  if (!folder.Has("results.csv") && !folder.Has("sweep.json")) return std::nullopt;
  Section s{"sweep", "Sweep", ""};
  if (folder.Has("sweep.json")) {
    const json j = ReadJson(folder.dir, "sweep.json");
    std::vector<std::pair<std::string, std::string>> facts;
    for (const char* key :
         {"name", "scenario_file", "mode", "parameters", "metrics", "repeats", "combinations",
          "cases", "shard", "cases_done", "complete", "merged_from"}) {
      if (j.is_object() && j.contains(key)) facts.emplace_back(key, HtmlEscape(Text(j[key])));
    }
    s.html += FactsTable(facts);
  }
  if (folder.Has("results.csv")) {
    const std::vector<io::CsvRecord> records = io::ReadCsvFile(folder.dir / "results.csv");
    if (records.empty()) {
      s.html += "<p class=\"note\">results.csv is empty.</p>\n";
      return s;
    }
    const std::size_t rows = records.size() - 1;
    const std::size_t shown = std::min(rows, kReportTableRows);
    s.html += "<h3>results.csv</h3>\n<p class=\"note\">" +
              (shown < rows ? "The first " + std::to_string(shown) + " of " + std::to_string(rows) +
                                  " rows (the whole table is in " + "results.csv)."
                            : std::to_string(rows) + (rows == 1 ? " row." : " rows.")) +
              "</p>\n<div class=\"scroll\"><table>\n<tr>";
    for (const std::string& cell : records[0].cells) s.html += "<th>" + HtmlEscape(cell) + "</th>";
    s.html += "</tr>\n";
    for (std::size_t r = 1; r <= shown; ++r) {
      s.html += "<tr>";
      for (const std::string& cell : records[r].cells) {
        const bool number = io::ParseCsvNumber(cell).has_value();
        s.html += std::string(number ? "<td class=\"num\">" : "<td>") + HtmlEscape(cell) + "</td>";
      }
      s.html += "</tr>\n";
    }
    s.html += "</table></div>\n";
  }
  return s;
}

// What a figure shows, by its file name (docs/FORMATS.md).
std::string Caption(const fs::path& rel) {
  const std::string name = rel.filename().string();
  static const std::vector<std::pair<std::string, std::string>> kKnown = {
      {"maps.png",
       "the taught route coloured per partial map with the switch points, then every partial "
       "map in its own frame (paper Fig. 1)"},
      {"maps_compare.png", "the consistent map next to the single odometry map (paper Fig. 6)"},
      {"odometry.png", "ground truth and wheel odometry of the teaching drive and run 0 (Fig. 8)"},
      {"likelihood.png",
       "the measurement likelihood around the true pose, without and with dynamic point "
       "rejection (Fig. 5)"},
      {"snapshot.png",
       "the update with the most pedestrian beams: particles, estimate, truth and the scan "
       "points rejected as dynamic (Fig. 4)"},
      {"errors.png", "tracking and localization error along the route, map switches marked"},
      {"comparison.png", "the modes' metrics side by side"},
      {"sweep.png", "each metric against each plotted parameter (mean over repeats, min–max)"},
      {"world.png", "the world and its route"},
  };
  for (const auto& [known, caption] : kKnown) {
    if (name == known) return caption;
  }
  if (name.starts_with("playback_"))
    return "the taught path and every run's trajectory, zoomed where the runs spread most (Fig. 7)";
  return "";
}

bool IsPng(const std::string& bytes) {
  return bytes.size() >= 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
}

Section FiguresSection(const Folder& folder, int* images) {
  std::map<std::string, std::vector<fs::path>> groups;  // by subfolder; "" first
  for (const fs::path& rel : folder.files) {
    std::string ext = rel.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".png") groups[Generic(rel.parent_path())].push_back(rel);
  }
  Section s{"figures", "Figures", ""};
  if (groups.empty()) {
    s.html = "<p class=\"note\">No PNG figures in this folder.</p>\n";
    return s;
  }
  for (const auto& [group, files] : groups) {
    s.html += "<h3>" + HtmlEscape(group.empty() ? "top level" : group + "/") + "</h3>\n";
    for (const fs::path& rel : files) {
      const std::string where = "<code>" + HtmlEscape(Generic(rel)) + "</code>";
      std::error_code ec;
      const std::uintmax_t size = fs::file_size(folder.dir / rel, ec);
      if (ec || size > kMaxImageBytes) {
        s.html += "<p class=\"note\">" + where + ": not embedded (" +
                  (ec ? "cannot read it" : std::to_string(size >> 20) + " MB") + ").</p>\n";
        continue;
      }
      const std::string bytes = io::ReadFileBytes(folder.dir / rel);
      if (!IsPng(bytes)) {
        s.html += "<p class=\"note\">" + where + ": not a PNG image, not embedded.</p>\n";
        continue;
      }
      const std::string caption = Caption(rel);
      s.html += "<figure><img alt=\"" + HtmlEscape(Generic(rel)) +
                "\" src=\"data:image/png;base64," + Base64Encode(bytes) + "\"><figcaption>" +
                where + (caption.empty() ? "" : ": " + HtmlEscape(caption)) +
                "</figcaption></figure>\n";
      ++*images;
    }
  }
  return s;
}

std::string YamlText(const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  return out.c_str();
}

// One manifest.yaml: its scalar keys as a table, its maps and lists folded away.
std::string ManifestHtml(const fs::path& dir, const fs::path& rel) {
  YAML::Node root;
  try {
    root = YAML::LoadFile((dir / rel).string());
  } catch (const YAML::Exception& e) {
    throw core::IoError((dir / rel).string() + ": cannot read the manifest: " + e.what());
  }
  if (!root.IsMap()) {
    throw core::IoError((dir / rel).string() +
                        ": cannot read the manifest: not a map of keys and values");
  }
  std::vector<std::pair<std::string, std::string>> facts;
  std::string folded;
  for (const auto& entry : root) {
    const std::string key = entry.first.Scalar();
    const YAML::Node& value = entry.second;
    if (value.IsScalar() || value.IsNull()) {
      facts.emplace_back(key, HtmlEscape(value.IsNull() ? "" : value.Scalar()));
    } else if (value.IsSequence() && value.size() == 0) {
      facts.emplace_back(key, "none");
    } else {
      folded += "<details><summary>" + HtmlEscape(key) + "</summary><pre>" +
                HtmlEscape(YamlText(value)) + "</pre></details>\n";
    }
  }
  return "<h3><code>" + HtmlEscape(Generic(rel)) + "</code></h3>\n" + FactsTable(facts) + folded;
}

// The command, revision and timing that sweep.json, a compare's comparison.json and a suite's
// report.json record (their folders have no manifest.yaml).
std::string RecordHtml(const Folder& folder, const fs::path& rel) {
  const json j = ReadJson(folder.dir, rel);
  if (!j.is_object()) return "";
  std::vector<std::pair<std::string, std::string>> facts;
  for (const char* key : {"command", "scenario", "scenario_file", "suite", "suite_file",
                          "sweep_file", "seeds", "repeats", "reference", "git_revision",
                          "build_type", "date", "jobs", "wall_time_s", "set", "only"}) {
    if (j.contains(key) && !(j[key].is_array() && j[key].empty()) && !j[key].is_object())
      facts.emplace_back(key, HtmlEscape(Text(j[key])));
  }
  if (facts.empty()) return "";
  return "<h3><code>" + HtmlEscape(Generic(rel)) + "</code></h3>\n" + FactsTable(facts);
}

std::optional<Section> ProvenanceSection(const Folder& folder) {
  std::string html;
  for (const fs::path& rel : folder.Named("manifest.yaml")) html += ManifestHtml(folder.dir, rel);
  for (const char* record : {"sweep.json", "comparison.json", "report.json"}) {
    if (folder.Has(record)) html += RecordHtml(folder, record);
  }
  if (html.empty()) return std::nullopt;
  return Section{"provenance", "Provenance", html};
}

Section FilesSection(const Folder& folder, bool open) {
  std::map<std::string, int> by_extension;
  for (const fs::path& rel : folder.files) {
    const std::string ext = rel.extension().string();
    ++by_extension[ext.empty() ? "(none)" : ext];
  }
  std::string counts;
  for (const auto& [ext, n] : by_extension)
    counts += (counts.empty() ? "" : ", ") + std::to_string(n) + " " + HtmlEscape(ext);
  Section s{"files", "Files", ""};
  s.html = "<p>" + std::to_string(folder.files.size()) + (folder.truncated ? "+" : "") +
           (folder.files.size() == 1 ? " file" : " files") +
           (counts.empty() ? "" : " (" + counts + ")") + ".</p>\n";
  if (folder.files.empty()) return s;
  s.html +=
      std::string("<details") + (open ? " open" : "") + "><summary>List" +
      (folder.files.size() > kListedFiles ? " (the first " + std::to_string(kListedFiles) + ")"
                                          : std::string()) +
      "</summary>\n<pre>";
  for (std::size_t i = 0; i < folder.files.size() && i < kListedFiles; ++i) {
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(folder.dir / folder.files[i], ec);
    s.html += HtmlEscape(Generic(folder.files[i])) +
              (ec ? std::string() : "  (" + std::to_string(size) + " bytes)") + "\n";
  }
  s.html += "</pre></details>\n";
  return s;
}

// What kind of folder this is, from the files that identify each command's output.
std::pair<std::string, std::string> Kind(const Folder& folder) {
  bool modes = false, manifests = false;
  for (const fs::path& rel : folder.Named("metrics.json"))
    modes = modes || !rel.parent_path().empty();
  for (const fs::path& rel : folder.Named("manifest.yaml"))
    manifests = manifests || !rel.parent_path().empty();
  if (folder.Has("report.json") || folder.Has("report.md"))
    return {"bench", "a regression suite's report (retrace bench)"};
  if (folder.Has("sweep.json")) return {"sweep", "a parameter sweep (retrace sweep / merge)"};
  if (folder.Has("metrics.json") && folder.Has("manifest.yaml"))
    return {"log-localize", "a recorded log localized in a teach folder (retrace log-localize)"};
  if (modes) return {"run", "the results of retrace run / playback, one folder per map mode"};
  if (folder.Has("comparison.json"))
    return {"compare", "a map-mode comparison over seeds (retrace compare)"};
  if (folder.Has("comparison.md"))
    return {"log-compare", "log-localize runs side by side (retrace log-compare)"};
  if (manifests) return {"teach", "teach folders (retrace teach / log-teach)"};
  return {"folder", "a folder retrace does not recognise: the page lists what it found"};
}

}  // namespace page
}  // namespace

std::string HtmlEscape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

HtmlReport BuildHtmlReport(const fs::path& dir) {
  const page::Folder folder = page::Walk(dir);
  const auto [kind, description] = page::Kind(folder);
  HtmlReport report;
  report.kind = kind;

  std::vector<page::Section> sections;
  auto add = [&](std::optional<page::Section> s) {
    if (s) sections.push_back(std::move(*s));
  };
  add(page::SuiteSection(folder));
  add(page::SummarySection(folder));
  add(page::ComparisonSection(folder));
  add(page::SweepSection(folder));
  sections.push_back(page::FiguresSection(folder, &report.images));
  add(page::ProvenanceSection(folder));
  sections.push_back(page::FilesSection(folder, kind == "folder"));

  fs::path shown = dir;
  if (shown.filename().empty()) shown = shown.parent_path();  // "results/x/"
  const std::string name = HtmlEscape(fs::absolute(shown).lexically_normal().filename().string());
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; "
      "style-src 'unsafe-inline'; script-src 'unsafe-inline'\">\n"
      "<title>retrace report: " +
      name + "</title>\n<style>" + page::kCss + "</style>\n</head>\n<body>\n<header>\n<h1>" + name +
      "</h1>\n<p>" + HtmlEscape(description) + "</p>\n<p><code>" + HtmlEscape(shown.string()) +
      "</code>, " + std::to_string(folder.files.size()) + " files, " +
      std::to_string(report.images) + " figures</p>\n<nav>";
  for (const page::Section& s : sections) html += "<a href=\"#" + s.id + "\">" + s.title + "</a>";
  html += "</nav>\n</header>\n<main>\n";
  for (const page::Section& s : sections) {
    html += "<section id=\"" + s.id + "\">\n<h2>" + s.title + "</h2>\n" + s.html + "</section>\n";
  }
  html += "</main>\n<script>" + std::string(page::kScript) + "</script>\n</body>\n</html>\n";
  report.html = std::move(html);
  return report;
}

HtmlReport WriteHtmlReport(const fs::path& dir) {
  HtmlReport report = BuildHtmlReport(dir);
  io::WriteFileAtomic(dir / "report.html", report.html);
  return report;
}

}  // namespace retrace::bench
