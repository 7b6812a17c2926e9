#pragma once
// `retrace bench <suite>`: runs a regression suite, compares every gated metric with the
// committed baseline under its tolerance, prints the table and a one-line verdict, and writes
// report.json and report.md; one library call (bench/suite/suite_bench.hpp). `--update-baseline`
// records the results as the new baseline instead of judging them. `--only <entry>[.<mode>]`
// runs and judges a part of the suite against the same baseline. For CI systems: `--junit FILE`
// writes the verdicts as JUnit XML, `--trend FILE` every metric in the Bencher Metric Format.

#include "bench/suite/suite_bench.hpp"

namespace CLI {
class App;
}

namespace retrace::bench {

struct BenchOptions {
  BenchRequest request;
  bool report = true;  ///< write report.html into the report folder at the end
};

/// Adds the options of `retrace bench` to a CLI11 subcommand.
void AddBenchOptions(CLI::App* command, BenchOptions* options);

/// Runs the command. Returns 0 (everything within tolerance, or a baseline recorded) or 1 (a
/// regression). Throws core::Error on bad input — a malformed suite, a missing or foreign
/// baseline, an unknown `--set` key, a --junit or --trend path that cannot be written — before
/// anything runs or is written.
int RunBenchCommand(const BenchOptions& options);

}  // namespace retrace::bench
