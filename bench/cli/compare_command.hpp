#pragma once
// `retrace compare`: the consistent-vs-partial study. For each of N scenario seeds one teaching
// drive builds the maps of every mode, and each mode plays back R runs with the same playback
// seeds; the per-seed metrics of the modes are then compared with confidence intervals over
// seeds (bench/compare/comparison_report.hpp). Writes comparison.json, comparison.md and
// comparison.png into one folder, published whole or not at all.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace retrace::bench {

struct CompareOptions {
  std::filesystem::path scenario;
  std::vector<std::string> modes = {"all"};
  std::string reference = "consistent";
  int seeds = 5;               ///< scenario seeds seed, seed + 1, ...; >= 2
  std::optional<int> repeats;  ///< playback runs per mode and seed; none: the scenario's
  int jobs = 0;                ///< worker threads; 0: one per core
  std::filesystem::path out;   ///< empty: results/compare/<scenario name>
  std::vector<std::string> overrides;
  bool report = true;  ///< write report.html at the end
};

/// Adds the command's arguments to a CLI11 subcommand.
void AddCompareOptions(CLI::App* command, CompareOptions* options);

/// Runs the study, writes the folder and prints the table on stdout. Returns 0. Throws
/// core::Error on bad input (unknown mode, reference not among the modes, fewer than two seeds,
/// a bad scenario or --set) before anything is run or written.
int RunCompareCommand(const CompareOptions& options, const std::string& command_line);

}  // namespace retrace::bench
