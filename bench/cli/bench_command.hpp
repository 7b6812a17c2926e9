#pragma once
// `retrace bench <suite>`: runs a regression suite (bench/suite/suite_spec.hpp), compares every
// gated metric with the committed baseline (bench/suite/baseline.hpp) under its tolerance
// (bench/suite/tolerance.hpp), prints the table and a one-line verdict, and writes report.json and
// report.md. `--update-baseline` records the results as the new baseline instead of judging
// them. `--only <entry>[.<mode>]` runs and judges a part of the suite against the same baseline.
// For CI systems: `--junit FILE` writes the verdicts as JUnit XML (bench/suite/junit_report.hpp),
// `--trend FILE` every metric in the Bencher Metric Format (bench/suite/trend_file.hpp).

#include <filesystem>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace retrace::bench {

struct BenchOptions {
  std::filesystem::path suite;
  std::filesystem::path baseline;  ///< empty: results/baselines/<suite name>.json
  bool update_baseline = false;
  int jobs = 0;                        ///< worker threads; 0: one per core
  std::filesystem::path out;           ///< report folder; empty: results/bench/<suite name>
  std::vector<std::string> overrides;  ///< --set, applied to every entry after its own `set`
  std::vector<std::string> only;       ///< --only <entry>[.<mode>]; empty: the whole suite
  bool report = true;                  ///< write report.html into `out` at the end
  std::filesystem::path junit;         ///< --junit: JUnit XML of the verdicts; empty: none
  std::filesystem::path trend;         ///< --trend: the metrics as BMF JSON; empty: none
};

/// Adds the options of `retrace bench` to a CLI11 subcommand.
void AddBenchOptions(CLI::App* command, BenchOptions* options);

/// Runs the command. Returns 0 (everything within tolerance, or a baseline recorded) or 1 (a
/// regression). Throws core::Error on bad input — a malformed suite, a missing or foreign
/// baseline, an unknown `--set` key, a --junit or --trend path that cannot be written — before
/// anything runs or is written.
int RunBenchCommand(const BenchOptions& options);

}  // namespace retrace::bench
