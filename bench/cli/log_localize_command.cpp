#include "bench/cli/log_localize_command.hpp"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "bench/cli/log_options.hpp"
#include "core/angle.hpp"
#include "core/errors.hpp"

namespace retrace::bench {

namespace {

// "x,y,yaw_deg" → a pose in map 0.
core::Pose2 ParseInitialPose(const std::string& text) {
  double x = 0.0, y = 0.0, yaw_deg = 0.0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &x, &y, &yaw_deg, &tail) != 3 ||
      !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(yaw_deg)) {
    throw core::ConfigError("--initial-pose",
                            "must be x,y,yaw_deg (m, m, degrees in map 0), got '" + text + "'");
  }
  return {x, y, core::DegToRad(yaw_deg)};
}

}  // namespace

void AddLogLocalizeOptions(CLI::App* cmd, LogLocalizeOptions* options) {
  LogLocalizeRequest& request = options->request;
  AddLogRunOptions(cmd, &request.run);
  cmd->add_option("--teach", request.teach_dir,
                  "The teach/ folder to localize in (<mode>/teach of log-teach or run)")
      ->required();
  cmd->add_option("--initial-pose", options->initial_pose,
                  "Where the robot starts, in map 0's frame: x,y,yaw_deg; it starts in the map "
                  "whose taught path is nearest (default: the map nearest the reference when "
                  "there is one, else map 0's origin)");
  cmd->add_flag("--every-odometry-tick", request.every_odometry_tick,
                "One prediction per odometry message, as the simulator's playback predicts "
                "(default: the fewest arcs that follow the messages within 1 mm)");
}

int RunLogLocalizeCommand(const LogLocalizeOptions& options, const std::string& command_line) {
  const auto wall_start = std::chrono::steady_clock::now();
  LogLocalizeRequest request = options.request;
  if (!options.initial_pose.empty()) request.initial = ParseInitialPose(options.initial_pose);
  const LogLocalization localized = LocalizeLog(request);
  const std::vector<std::string> notes = WriteLogLocalizeFolder(
      localized, command_line,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
  std::cout << LogLocalizeSummary(localized) << "\n";
  for (const std::string& note : notes)
    std::cout << "  " << (note.starts_with("warning: ") ? "" : "note: ") << note << "\n";
  return 0;
}

}  // namespace retrace::bench
