#pragma once
// `retrace sweep <file>`: runs the cases of a sweep file (bench/sweep/sweep_spec.hpp) in parallel,
// one row per case appended to <out>/results.csv as each finishes; resumes an interrupted
// sweep where it stopped; runs one shard of the cases (`--shard i/N`) for a batch scheduler;
// at the end rewrites results.csv sorted by case id and plots sweep.png. The results do not
// depend on --jobs or on interruptions.

#include <filesystem>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace retrace::bench {

struct SweepOptions {
  std::filesystem::path file;
  int jobs = 0;                        ///< cases at once; 0: one per core
  std::filesystem::path out;           ///< empty: DefaultSweepFolder
  std::string shard;                   ///< "i/N"; empty: all cases
  std::vector<std::string> overrides;  ///< --set, applied to every case
  bool plot = true;
  bool report = true;  ///< write report.html at the end (a shard's too)
};

/// Adds the command's arguments to a CLI11 subcommand.
void AddSweepOptions(CLI::App* command, SweepOptions* options);

/// Runs the sweep; prints a summary on stdout. Returns 0. Throws core::Error on bad input
/// (before anything is written: the sweep file, every combination, the shard, a folder holding
/// another sweep) and when a case cannot run (the rows of the finished cases stay).
int RunSweepCommand(const SweepOptions& options, const std::string& command_line);

}  // namespace retrace::bench
