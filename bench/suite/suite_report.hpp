#pragma once
// The comparison of a suite's results with its baseline: one row per metric that a suite
// rule decides (bench/suite/suite_spec.hpp), with the verdict of bench/suite/tolerance.hpp, and the
// renderings of it: the table `retrace bench` prints, report.md and report.json.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench/suite/baseline.hpp"
#include "bench/suite/suite_runner.hpp"
#include "bench/suite/suite_spec.hpp"
#include "bench/suite/tolerance.hpp"

namespace retrace::bench {

struct ReportRow {
  std::string name;                ///< "<entry>.<mode>.<metric>"
  std::optional<double> baseline;  ///< nullopt: not in the baseline (or no baseline)
  std::optional<double> now;       ///< nullopt: no longer computed
  double seed_sd = 0.0;            ///< sample standard deviation over the seeds (NaN with < 2)
  std::string pattern;             ///< of the deciding rule
  Tolerance tolerance;
  MetricCheck check;
};

struct SuiteReport {
  std::string suite;
  bool compared = false;  ///< false: no baseline to compare with (recording the first one)
  std::vector<ReportRow> rows;
  int failures = 0;
  int improved = 0;
  int reported = 0;
  int checked = 0;  ///< gated rows (not `report`)
};

/// Compares `results` with `baseline` (nullptr: only lists the values).
SuiteReport CompareWithBaseline(const SuiteSpec& spec, const SuiteResults& results,
                                const Baseline* baseline);

/// now - baseline; nullopt unless both are finite numbers.
std::optional<double> RowDelta(const ReportRow& row);

/// A value as the table shows it: 4 significant digits, "-" when missing, "nan" when undefined.
std::string FormatValue(std::optional<double> v);

/// A delta as the table shows it: signed, 3 significant digits, "-" when missing.
std::string FormatDelta(std::optional<double> v);

/// The table printed on stdout: metric, baseline, now, delta, verdict, tolerance and why.
std::string ReportTable(const SuiteReport& report);

/// Where the numbers come from, for report.md and report.json.
struct ReportContext {
  std::filesystem::path suite_file;
  std::string suite_digest;
  std::filesystem::path baseline_file;
  const Baseline* baseline = nullptr;  ///< the baseline compared with, if any
  std::string git_revision;
  std::string date;
  double wall_time_s = 0.0;
  int jobs = 0;
  std::vector<std::string> overrides;  ///< --set of the command line
  std::vector<std::string> only;       ///< --only of the command line (empty: the whole suite)
  std::string version;                 ///< retrace's own version (BuildVersion())
  bool recording = false;  ///< --update-baseline: the results become the baseline, nothing fails
};

std::string ReportMarkdown(const SuiteReport& report, const ReportContext& context);

/// The provenance report.json records: git revision, date, wall time, jobs, --set and --only.
Provenance ReportProvenance(const ReportContext& context);

/// The rows, plus every metric's mean and per-seed values (to measure seed-to-seed spreads).
nlohmann::json ReportJson(const SuiteReport& report, const ReportContext& context,
                          const SuiteSpec& spec, const SuiteResults& results);

/// Sample standard deviation (n - 1) of the finite values; NaN with fewer than two.
double SeedStdDev(const std::vector<double>& values);

}  // namespace retrace::bench
