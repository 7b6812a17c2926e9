#pragma once
// `retrace log-teach <log> --out DIR`: the teach folders of a recorded log, one per map mode, as
// `retrace teach` writes them for a simulated drive: the options of
// bench/replay/log_teach_run.hpp's TeachLog, which it calls; prints its summary.

#include <string>
#include <vector>

#include "bench/replay/log_run_options.hpp"
#include "bench/replay/log_teach_run.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

struct LogTeachOptions {
  LogTeachRequest request;         ///< its extra_overrides and modes come from the two below
  std::string switch_points;       ///< auto, online or s1,s2,... (empty: the config's)
  std::vector<std::string> modes;  ///< --mode
};

/// Adds the options of LogRunOptions, which the log commands share, to `cmd`.
void AddLogRunOptions(CLI::App* cmd, LogRunOptions* options);
void AddLogTeachOptions(CLI::App* cmd, LogTeachOptions* options);

/// Runs log-teach; returns the exit code (0). Throws core::Error for bad input, before anything
/// is written.
int RunLogTeachCommand(const LogTeachOptions& options, const std::string& command_line);

}  // namespace retrace::bench
