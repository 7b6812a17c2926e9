#pragma once
// `retrace run`, `retrace teach` and `retrace playback`: teaching drive, playback runs,
// metrics and result files for the map modes of a scenario, as one library call
// (bench/run/scenario_run.hpp).

#include <string>

#include "bench/run/scenario_run.hpp"

namespace CLI {
class App;
}

namespace retrace::bench {

struct RunOptions {
  ScenarioRunRequest request;  ///< its `phases` are the command's
  bool report = true;          ///< write report.html at the end (bench/output/html_report)
};

/// Adds the options shared by run / teach / playback to a CLI11 subcommand.
void AddRunOptions(CLI::App* command, RunOptions* options, RunPhases phases);

/// Runs the command; prints the summary on stdout. Returns the exit code: 0, or 1 when a run of
/// a mode in limits.success_required failed. Throws core::Error on bad input, before anything
/// is written.
int RunRunCommand(const RunOptions& options, RunPhases phases, const std::string& command_line);

}  // namespace retrace::bench
