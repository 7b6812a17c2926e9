#pragma once
// `retrace compare`: the consistent-vs-partial study. For each of N scenario seeds one teaching
// drive builds the maps of every mode, and each mode plays back R runs with the same playback
// seeds; the per-seed metrics of the modes are then compared with confidence intervals over
// seeds. The study is one library call (bench/compare/comparison_study.hpp); it writes
// comparison.json, comparison.md and comparison.png into one folder, published whole or not at
// all.

#include <string>

#include "bench/compare/comparison_study.hpp"

namespace CLI {
class App;
}

namespace retrace::bench {

struct CompareOptions {
  ComparisonRequest request;
  bool report = true;  ///< write report.html at the end
};

/// Adds the command's arguments to a CLI11 subcommand.
void AddCompareOptions(CLI::App* command, CompareOptions* options);

/// Runs the study, writes the folder and prints the table on stdout. Returns 0. Throws
/// core::Error on bad input (unknown mode, reference not among the modes, fewer than two seeds,
/// a bad scenario or --set) before anything is run or written.
int RunCompareCommand(const CompareOptions& options, const std::string& command_line);

}  // namespace retrace::bench
