#include "bench/suite/suite_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <set>

#include "bench/suite/metric_pattern.hpp"
#include "core/format.hpp"

namespace retrace::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string VerdictText(const SuiteReport& report, const ReportRow& row) {
  return report.compared ? std::string(core::EnumName(row.check.verdict)) : std::string("new");
}

std::string Why(const SuiteReport& report, const ReportRow& row) {
  const std::string tolerance = DescribeTolerance(row.tolerance);
  if (!report.compared || row.check.reason.empty()) return tolerance;
  return tolerance + "; " + row.check.reason;
}

nlohmann::json JsonNumber(std::optional<double> v) {
  if (!v || !std::isfinite(*v)) return nullptr;
  return *v;
}

}  // namespace

std::string FormatValue(std::optional<double> v) {
  if (!v) return "-";
  if (std::isnan(*v)) return "nan";
  return core::Printf("%.4g", *v);
}

std::optional<double> RowDelta(const ReportRow& row) {
  if (!row.baseline || !row.now || !std::isfinite(*row.baseline) || !std::isfinite(*row.now))
    return std::nullopt;
  return *row.now - *row.baseline;
}

std::string FormatDelta(std::optional<double> v) {
  if (!v) return "-";
  return core::Printf("%+.3g", *v);
}

double SeedStdDev(const std::vector<double>& values) {
  std::vector<double> finite;
  for (double v : values) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  if (finite.size() < 2) return kNaN;
  double mean = 0.0;
  for (double v : finite) mean += v;
  mean /= static_cast<double>(finite.size());
  double sum = 0.0;
  for (double v : finite) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / static_cast<double>(finite.size() - 1));
}

namespace {

// The suite's metrics in its order, then any the baseline has that are no longer computed.
std::vector<std::string> ReportNames(const SuiteSpec& spec, const Baseline* baseline) {
  std::vector<std::string> names = SuiteMetricNames(spec);
  if (baseline == nullptr) return names;
  const std::set<std::string> known(names.begin(), names.end());
  for (const auto* table : {&baseline->metrics, &baseline->timing}) {
    for (const auto& [name, value] : *table) {
      if (!known.contains(name)) names.push_back(name);
    }
  }
  return names;
}

// The row of metric `name`, decided by `rule`: its value now, the baseline's and the verdict.
ReportRow MakeRow(const std::string& name, const MetricRule& rule, const SuiteResults& results,
                  const Baseline* baseline) {
  ReportRow row;
  row.name = name;
  row.pattern = rule.pattern;
  row.tolerance = rule.tolerance;
  row.seed_sd = kNaN;
  if (const auto it = results.metrics.find(name); it != results.metrics.end()) {
    row.now = it->second.mean;
    row.seed_sd = SeedStdDev(it->second.per_seed);
  }
  if (baseline != nullptr) row.baseline = baseline->Find(name);
  // The metric part of the name, after "<entry>.<mode>.", sets the direction and the timing rule.
  const std::string metric = SplitSuiteMetricName(name).metric;
  if (!row.now) {
    row.check = {Verdict::kFail, "no longer computed"};
  } else {
    row.check = CheckMetric(metric, row.baseline, *row.now, rule.tolerance);
  }
  return row;
}

}  // namespace

SuiteReport CompareWithBaseline(const SuiteSpec& spec, const SuiteResults& results,
                                const Baseline* baseline) {
  SuiteReport report;
  report.suite = spec.name;
  report.compared = baseline != nullptr;
  std::vector<std::string> patterns;
  for (const MetricRule& rule : spec.rules) patterns.push_back(rule.pattern);
  const std::vector<std::string> names = ReportNames(spec, baseline);

  // Rows by entry and mode, then in the order of the rules that decide them.
  const std::size_t block_size = AggregateMetricNames().size();
  std::vector<std::pair<std::size_t, int>> order_keys;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const int decider = DecidingPattern(patterns, names[i]);
    if (decider < 0) continue;
    order_keys.emplace_back(i / block_size, decider);
    ReportRow row =
        MakeRow(names[i], spec.rules[static_cast<std::size_t>(decider)], results, baseline);
    if (report.compared) {
      if (IsFailure(row.check.verdict)) ++report.failures;
      if (row.check.verdict == Verdict::kImproved) ++report.improved;
    }
    if (row.check.verdict == Verdict::kReport) {
      ++report.reported;
    } else {
      ++report.checked;
    }
    report.rows.push_back(std::move(row));
  }
  std::vector<std::size_t> order(report.rows.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return order_keys[a] < order_keys[b]; });
  std::vector<ReportRow> sorted;
  for (std::size_t i : order) sorted.push_back(std::move(report.rows[i]));
  report.rows = std::move(sorted);
  return report;
}

std::string ReportTable(const SuiteReport& report) {
  std::size_t width = 6;
  for (const ReportRow& row : report.rows) width = std::max(width, row.name.size());
  std::string text;
  char line[1024];
  std::snprintf(line, sizeof line, "%-*s %10s %10s %10s  %-8s  %s\n", static_cast<int>(width),
                "metric", "baseline", "now", "delta", "verdict", "tolerance");
  text += line;
  for (const ReportRow& row : report.rows) {
    std::snprintf(line, sizeof line, "%-*s %10s %10s %10s  %-8s  %s\n", static_cast<int>(width),
                  row.name.c_str(), FormatValue(row.baseline).c_str(), FormatValue(row.now).c_str(),
                  FormatDelta(RowDelta(row)).c_str(), VerdictText(report, row).c_str(),
                  Why(report, row).c_str());
    text += line;
  }
  return text;
}

std::string ReportMarkdown(const SuiteReport& report, const ReportContext& context) {
  std::string md = "# Suite " + report.suite + ": ";
  if (!report.compared) {
    md += "baseline recorded\n\n";
  } else {
    md += report.failures > 0 ? "FAIL (" + std::to_string(report.failures) + " regressions)\n\n"
                              : "pass\n\n";
  }
  md += "- suite: `" + context.suite_file.string() + "` (" + context.suite_digest + ")\n";
  if (context.baseline != nullptr) {
    md += "- baseline: `" + context.baseline_file.string() + "`, git " +
          context.baseline->git_revision + ", " + context.baseline->build_type + ", " +
          context.baseline->date + "\n";
  }
  md += "- now: git " + context.git_revision + ", " + context.date + ", " +
        std::to_string(context.jobs) + " jobs, " + FormatValue(context.wall_time_s) + " s\n";
  for (const std::string& o : context.overrides) md += "- `--set " + o + "`\n";
  for (const std::string& o : context.only) md += "- `--only " + o + "`\n";
  md +=
      "\n| metric | baseline | now | delta | seed sd | verdict | tolerance "
      "|\n|---|---:|---:|---:|---:|---|---|\n";
  for (const ReportRow& row : report.rows) {
    const std::string verdict = VerdictText(report, row);
    md += "| " + row.name + " | " + FormatValue(row.baseline) + " | " + FormatValue(row.now) +
          " | " + FormatDelta(RowDelta(row)) + " | " +
          FormatValue(std::isnan(row.seed_sd) ? std::nullopt : std::optional<double>(row.seed_sd)) +
          " | " +
          (IsFailure(row.check.verdict) && report.compared ? "**" + verdict + "**" : verdict) +
          " | " + Why(report, row) + " |\n";
  }
  return md;
}

Provenance ReportProvenance(const ReportContext& context) {
  Provenance p;
  p.git_revision = context.git_revision;
  p.date = context.date;
  p.wall_time_s = context.wall_time_s;
  p.jobs = context.jobs;
  p.overrides = context.overrides;
  p.only = context.only;
  return p;
}

nlohmann::json ReportJson(const SuiteReport& report, const ReportContext& context,
                          const SuiteSpec& spec, const SuiteResults& results) {
  nlohmann::json rows = nlohmann::json::array();
  for (const ReportRow& row : report.rows) {
    rows.push_back(
        {{"metric", row.name},
         {"baseline", JsonNumber(row.baseline)},
         {"now", JsonNumber(row.now)},
         {"delta", JsonNumber(RowDelta(row))},
         {"seed_sd", JsonNumber(row.seed_sd)},
         {"pattern", row.pattern},
         {"tolerance", DescribeTolerance(row.tolerance)},
         {"verdict", report.compared ? std::string(core::EnumName(row.check.verdict)) : "new"},
         {"reason", row.check.reason}});
  }
  nlohmann::json metrics = nlohmann::json::object();
  for (const auto& [name, metric] : results.metrics) {
    nlohmann::json per_seed = nlohmann::json::array();
    for (double v : metric.per_seed) per_seed.push_back(JsonNumber(v));
    metrics[name] = {{"mean", JsonNumber(metric.mean)}, {"per_seed", per_seed}};
  }
  nlohmann::json entries = nlohmann::json::array();
  for (const SuiteEntry& entry : spec.entries) entries.push_back(EntryDefinition(entry));
  nlohmann::json baseline = nullptr;
  if (context.baseline != nullptr) {
    baseline = {{"file", context.baseline_file.string()},
                {"git_revision", context.baseline->git_revision},
                {"build_type", context.baseline->build_type},
                {"date", context.baseline->date}};
  }
  nlohmann::json json = {{"suite", report.suite},
                         {"suite_file", context.suite_file.string()},
                         {"suite_digest", context.suite_digest},
                         {"baseline", baseline},
                         {"verdict", !report.compared      ? "recorded"
                                     : report.failures > 0 ? "FAIL"
                                                           : "pass"},
                         {"counts",
                          {{"checked", report.checked},
                           {"failures", report.failures},
                           {"improved", report.improved},
                           {"reported", report.reported}}},
                         {"entries", entries},
                         {"rows", rows},
                         {"metrics", metrics}};
  WriteProvenance(ReportProvenance(context), &json);
  return json;
}

}  // namespace retrace::bench
