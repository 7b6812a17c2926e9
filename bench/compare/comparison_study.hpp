#pragma once
// `retrace compare` as one library call: the consistent-vs-partial study of a scenario over
// several seeds (RunComparisonStudy), written into one folder published whole or not at all
// (comparison.json, comparison.md, comparison.png), and what it found (ComparisonStudySummary).
// The command line and the Python module call these.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/compare/comparison_report.hpp"
#include "bench/engine/progress.hpp"

namespace retrace::bench {

struct ComparisonRequest {
  std::filesystem::path scenario;
  std::vector<std::string> modes = {"all"};  ///< mode names, or {"all"}
  /// Stacks to put side by side (playback.stack names), each in every mode, on the same seeds;
  /// empty: the scenario's own. The reference is the reference mode with the first stack.
  std::vector<std::string> stacks;
  std::string reference = "consistent";
  int seeds = 5;                       ///< scenario seeds seed, seed + 1, ...; >= 2
  std::optional<int> repeats;          ///< playback runs per mode and seed; none: the scenario's
  int jobs = 0;                        ///< worker threads; 0: one per core
  std::filesystem::path out;           ///< empty: results/compare/<scenario name>
  std::vector<std::string> overrides;  ///< a.b.c=value
};

/// A study done and its folder written.
struct ComparisonStudy {
  std::filesystem::path out;  ///< the folder written
  Comparison comparison;
  std::string markdown;  ///< comparison.md
};

/// Runs the study (progress and the scenario's warnings to `progress`, which may be null) and
/// writes its folder; `command_line` is recorded. Throws core::Error on bad input (unknown mode,
/// reference not among the modes, fewer than two seeds, a bad scenario or --set) before
/// anything is run or written.
ComparisonStudy RunComparisonStudy(const ComparisonRequest& request,
                                   const std::string& command_line, ProgressSink* progress);

/// What the command line prints: the table and the files written (no trailing newline).
std::string ComparisonStudySummary(const ComparisonStudy& study);

}  // namespace retrace::bench
