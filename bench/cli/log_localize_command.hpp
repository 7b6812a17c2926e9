#pragma once
// `retrace log-localize <log> --teach DIR --out DIR`: the options of
// bench/replay/log_localize_run.hpp's LocalizeLog, which it calls; prints its summary.

#include <filesystem>
#include <string>

#include "bench/cli/log_teach_command.hpp"
#include "bench/replay/log_localize_run.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

struct LogLocalizeOptions {
  LogLocalizeRequest request;
  std::string initial_pose;  ///< --initial-pose x,y,yaw_deg in map 0; empty: automatic
};

void AddLogLocalizeOptions(CLI::App* cmd, LogLocalizeOptions* options);

/// Runs log-localize; returns the exit code (0). Throws core::Error for bad input, before
/// anything is written.
int RunLogLocalizeCommand(const LogLocalizeOptions& options, const std::string& command_line);

}  // namespace retrace::bench
