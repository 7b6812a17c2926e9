#include "bench/output/html_report.hpp"
#include "bench/output/html_report_markdown.hpp"
#include "bench/output/internal/report_page.hpp"
#include "core/errors.hpp"
#include "io/csv_reader.hpp"
#include "io/read_file.hpp"

namespace retrace::bench::report {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

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

// The folder's metrics.json files as columns, in mode order: a run's aggregate, or a
// log-localize run's whole file without its runs.
std::vector<MetricsColumn> ReadMetricsColumns(const Folder& folder) {
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
  std::stable_sort(columns.begin(), columns.end(), [](const auto& a, const auto& b) {
    return ModeOrder(a.label) < ModeOrder(b.label);
  });
  return columns;
}

// The head row: a column per metrics file, titled with its path.
std::string MetricsHeadRow(const std::vector<MetricsColumn>& columns) {
  std::string head = "<tr><th>metric</th>";
  for (const MetricsColumn& c : columns)
    head += "<th title=\"" + HtmlEscape(Generic(c.file)) + "\">" + HtmlEscape(c.label) + "</th>";
  head += "</tr>\n";
  return head;
}

// The summary's rows: success, outcomes, then the headline metrics; a row only where a column
// has its value.
std::string HeadlineRows(const std::vector<MetricsColumn>& columns) {
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
  return rows;
}

// Every metric of any column, flattened, a row each in name order.
struct EveryMetricRows {
  std::string html;
  std::size_t count = 0;
};

EveryMetricRows AllMetricsRows(const std::vector<MetricsColumn>& columns) {
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
  return {all, names.size()};
}

// The suite's verdict, its counts and the baseline it was compared with, as one paragraph.
std::string SuiteVerdictParagraph(const json& j) {
  const std::string verdict = j.contains("verdict") ? Text(j["verdict"]) : "?";
  const bool failed = verdict == "FAIL";
  std::string html = "<p>Suite <strong>" +
                     HtmlEscape(j.contains("suite") ? Text(j["suite"]) : "?") +
                     "</strong>: <span class=\"" + (failed ? "fail-text" : "pass-text") + "\">" +
                     HtmlEscape(verdict) + "</span>";
  if (const json* counts = Find(j, "counts"); counts != nullptr && counts->is_object()) {
    std::string parts;
    for (const auto& [key, value] : counts->items())
      parts += (parts.empty() ? "" : ", ") + HtmlEscape(key) + " " + HtmlEscape(Text(value));
    html += " (" + parts + ")";
  }
  if (const json* b = Find(j, "baseline"); b != nullptr && b->is_object()) {
    html += "; baseline <code>" + HtmlEscape(b->contains("file") ? Text((*b)["file"]) : "?") +
            "</code>";
    if (b->contains("git_revision")) html += ", git " + HtmlEscape(Text((*b)["git_revision"]));
    if (b->contains("date")) html += ", " + HtmlEscape(Text((*b)["date"]));
  }
  return html + "</p>\n";
}

// A field of a suite report row, null when it has none.
json SuiteRowValue(const json& row, const char* key) {
  return row.contains(key) ? row[key] : json(nullptr);
}

// The baseline, now and delta cells of a suite report row.
std::string SuiteNumberCells(const json& row) {
  const json delta = SuiteRowValue(row, "delta");
  return "<td class=\"num\">" + HtmlEscape(Text(SuiteRowValue(row, "baseline"))) +
         "</td><td class=\"num\">" + HtmlEscape(Text(SuiteRowValue(row, "now"))) +
         "</td><td class=\"num\">" +
         HtmlEscape(delta.is_number() ? SignedNumber(delta.get<double>()) : Text(delta)) + "</td>";
}

// The suite report's rows as HTML: the regressions' (FAIL) rows and every metric's rows.
struct SuiteRowsHtml {
  std::string regressions;
  std::string all;
  int failures = 0;
};

SuiteRowsHtml SuiteTableRows(const json& rows) {
  SuiteRowsHtml out;
  for (const json& row : rows) {
    if (!row.is_object()) continue;
    const std::string v = Text(SuiteRowValue(row, "verdict"));
    const std::string name = HtmlEscape(Text(SuiteRowValue(row, "metric")));
    const std::string tolerance = HtmlEscape(Text(SuiteRowValue(row, "tolerance")));
    if (v == "FAIL") {
      ++out.failures;
      out.regressions += "<tr class=\"fail\"><td>" + name + "</td>" + SuiteNumberCells(row) +
                         "<td>" + tolerance + "</td><td>" +
                         HtmlEscape(Text(SuiteRowValue(row, "reason"))) + "</td></tr>\n";
    }
    const std::string cls = v == "FAIL"       ? " class=\"fail\""
                            : v == "improved" ? " class=\"improved\""
                                              : "";
    out.all += "<tr" + cls + "><td>" + name + "</td>" + SuiteNumberCells(row) +
               Cell(SuiteRowValue(row, "seed_sd")) + "<td>" + HtmlEscape(v) + "</td><td>" +
               tolerance + "</td><td><code>" + HtmlEscape(Text(SuiteRowValue(row, "pattern"))) +
               "</code></td></tr>\n";
  }
  return out;
}

}  // namespace

std::optional<Section> SummarySection(const Folder& folder) {
  const std::vector<MetricsColumn> columns = ReadMetricsColumns(folder);
  if (columns.empty()) return std::nullopt;
  const std::string head = MetricsHeadRow(columns);
  const std::string rows = HeadlineRows(columns);
  const EveryMetricRows all = AllMetricsRows(columns);

  Section s{"summary", "Summary", ""};
  std::string files;
  for (const MetricsColumn& c : columns)
    files += (files.empty() ? "" : ", ") + ("<code>" + HtmlEscape(Generic(c.file)) + "</code>");
  s.html = "<p class=\"note\">From " + files +
           (columns.front().values.contains("runs") ? "; pooled over each mode's runs." : ".") +
           "</p>\n<div class=\"scroll\"><table>\n" + head + rows +
           "</table></div>\n<details><summary>All " + std::to_string(all.count) +
           " metrics</summary>\n<div class=\"scroll\"><table>\n" + head + all.html +
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
  Section s{"suite", "Regression suite", SuiteVerdictParagraph(j)};
  const SuiteRowsHtml rows = SuiteTableRows(j["rows"]);
  s.html += "<h3>Regressions</h3>\n";
  if (rows.failures == 0) {
    s.html += "<p class=\"pass-text\">None: every gated metric is within its tolerance.</p>\n";
  } else {
    s.html +=
        "<div class=\"scroll\"><table>\n<tr><th>metric</th><th>baseline</th><th>now</th>"
        "<th>delta</th><th>tolerance</th><th>why</th></tr>\n" +
        rows.regressions + "</table></div>\n";
  }
  s.html +=
      "<h3>Every metric</h3>\n<div class=\"scroll\"><table>\n<tr><th>metric</th>"
      "<th>baseline</th><th>now</th><th>delta</th><th>seed sd</th><th>verdict</th>"
      "<th>tolerance</th><th>pattern</th></tr>\n" +
      rows.all + "</table></div>\n";
  return s;
}

namespace {

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

}  // namespace

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

}  // namespace retrace::bench::report
