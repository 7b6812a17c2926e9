#pragma once
// `retrace bench <suite>` as one library call (RunBench): runs a regression suite
// (bench/suite/suite_spec.hpp), compares every gated metric with the committed baseline
// (bench/suite/baseline.hpp) under its tolerance (bench/suite/tolerance.hpp), and writes
// report.json and report.md. `update_baseline` records the results as the new baseline instead
// of judging them. `only` (<entry>[.<mode>]) runs and judges a part of the suite against the
// same baseline. For CI systems: `junit` writes the verdicts as JUnit XML
// (bench/suite/junit_report.hpp), `trend` every metric in the Bencher Metric Format
// (bench/suite/trend_file.hpp). BenchSummary is the table and the one-line verdict. The command
// line and the Python module call these.

#include <filesystem>
#include <string>
#include <vector>

#include "bench/engine/progress.hpp"
#include "bench/suite/suite_report.hpp"

namespace retrace::bench {

struct BenchRequest {
  std::filesystem::path suite;
  std::filesystem::path baseline;  ///< empty: results/baselines/<suite name>.json
  bool update_baseline = false;
  int jobs = 0;                        ///< worker threads; 0: one per core
  std::filesystem::path out;           ///< report folder; empty: results/bench/<suite name>
  std::vector<std::string> overrides;  ///< --set, applied to every entry after its own `set`
  std::vector<std::string> only;       ///< <entry>[.<mode>]; empty: the whole suite
  std::filesystem::path junit;         ///< JUnit XML of the verdicts; empty: none
  std::filesystem::path trend;         ///< the metrics as BMF JSON; empty: none
};

/// A suite run, judged, and its report written.
struct BenchRun {
  std::filesystem::path out;  ///< the report folder
  SuiteReport report;
  std::string verdict;  ///< one line, no newline
  /// 0 (everything within tolerance, or a baseline recorded) or 1 (a regression).
  int exit_code = 0;
};

/// Runs the suite (progress and the scenarios' warnings to `progress`, may be null), judges it
/// and writes the report, the baseline when recording one, and the CI systems' files. Throws
/// core::Error on bad input — a malformed suite, a missing or foreign baseline, an unknown
/// `--set` key, a junit or trend path that cannot be written — before anything runs or is
/// written.
BenchRun RunBench(const BenchRequest& request, ProgressSink* progress);

/// The table and the verdict line, as the command line prints them (no trailing newline).
std::string BenchSummary(const BenchRun& run);

}  // namespace retrace::bench
