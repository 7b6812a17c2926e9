#pragma once
// `retrace sweep <file>`: runs the cases of a sweep file (bench/sweep/sweep_spec.hpp) in parallel,
// one row per case appended to <out>/results.csv as each finishes; resumes an interrupted
// sweep where it stopped; runs one shard of the cases (`--shard i/N`) for a batch scheduler;
// at the end rewrites results.csv sorted by case id and plots sweep.png. The results do not
// depend on --jobs or on interruptions. One library call (bench/sweep/sweep_run.hpp).

#include <string>

#include "bench/sweep/sweep_run.hpp"

namespace CLI {
class App;
}

namespace retrace::bench {

struct SweepOptions {
  SweepRequest request;
  bool report = true;  ///< write report.html at the end (a shard's too)
};

/// Adds the command's arguments to a CLI11 subcommand.
void AddSweepOptions(CLI::App* command, SweepOptions* options);

/// Runs the sweep; prints a summary on stdout. Returns 0. Throws core::Error on bad input
/// (before anything is written: the sweep file, every combination, the shard, a folder holding
/// another sweep) and when a case cannot run (the rows of the finished cases stay).
int RunSweepCommand(const SweepOptions& options, const std::string& command_line);

}  // namespace retrace::bench
