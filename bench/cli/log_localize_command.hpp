#pragma once
// `retrace log-localize <log> --teach DIR --out DIR`: the localizer and the map server of
// playback run through a recorded log in the maps of a teach folder (bench/replay/
// log_localize.hpp); writes the estimate, the metrics against the reference and the figures.

#include <filesystem>
#include <string>

#include "bench/cli/log_teach_command.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

struct LogLocalizeOptions {
  LogRunOptions run;
  std::filesystem::path teach_dir;
  std::string initial_pose;  ///< x,y,yaw_deg in map 0; empty: automatic
  bool every_odometry_tick = false;  ///< one prediction per odometry message
};

void AddLogLocalizeOptions(CLI::App* cmd, LogLocalizeOptions* options);

/// Runs log-localize; returns the exit code (0). Throws core::Error for bad input, before
/// anything is written.
int RunLogLocalizeCommand(const LogLocalizeOptions& options, const std::string& command_line);

}  // namespace retrace::bench
