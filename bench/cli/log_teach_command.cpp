#include "bench/cli/log_teach_command.hpp"

#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>

#include "bench/cli/log_options.hpp"
#include "bench/cli/shared_options.hpp"
#include "bench/engine/mode_list.hpp"

namespace retrace::bench {

namespace {

// --switch-points auto|online|s1,s2,... as the key route.switch_points.
std::string SwitchPointsOverride(const std::string& text) {
  if (text == "auto" || text == "online") return "route.switch_points=" + text;
  return "route.switch_points=[" + text + "]";
}

}  // namespace

void AddLogRunOptions(CLI::App* cmd, LogRunOptions* options) {
  AddLogArgument(cmd, &options->log);
  AddOutOption(cmd, &options->out, "Results folder to write")->required();
  AddWindowOptions(cmd, &options->window);
  cmd->add_flag("--synthetic-odometry", options->synthetic_odometry,
                "Draw drifting odometry from the reference (or from the log's odometry, which "
                "then becomes the reference) with the simulator's model: sim.odometry, seed");
  AddReferenceOption(cmd, &options->reference);
  AddConfigOption(cmd, &options->config,
                  "Settings file (YAML): seed, modes, route, sim.odometry, nav, playback, metrics");
  AddSetOption(cmd, &options->overrides, "a setting: a.b.c=value");
  AddSeedOption(cmd, &options->seed, "of the synthetic odometry and the localizer");
  AddNoFiguresFlag(cmd, &options->figures);
  AddStreamOptions(cmd, &options->streams);
}

void AddLogTeachOptions(CLI::App* cmd, LogTeachOptions* options) {
  AddLogRunOptions(cmd, &options->request.run);
  cmd->add_option("--switch-points", options->switch_points,
                  "Where maps switch: online (the recorder decides), auto (from the driven "
                  "path) or arc lengths along it, s1,s2,... (m); default online");
  cmd->add_option("--mode", options->modes,
                  "Map modes: partial|single|consistent|scan_matched, comma-separated (default: "
                  "partial, scan_matched and, with a reference, consistent)")
      ->delimiter(',');
}

int RunLogTeachCommand(const LogTeachOptions& options, const std::string& command_line) {
  const auto wall_start = std::chrono::steady_clock::now();
  LogTeachRequest request = options.request;
  if (!options.switch_points.empty())
    request.extra_overrides.push_back(SwitchPointsOverride(options.switch_points));
  if (!options.modes.empty()) request.modes = ParseModeList(options.modes, "--mode");
  const LogTeaching taught = TeachLog(request);
  const std::vector<std::string> notes = WriteLogTeachFolder(
      taught, command_line,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
  std::cout << LogTeachSummary(taught, notes) << "\n";
  return 0;
}

}  // namespace retrace::bench
