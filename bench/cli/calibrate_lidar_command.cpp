#include "bench/cli/calibrate_lidar_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "bench/cli/log_options.hpp"
#include "bench/cli/shared_options.hpp"

namespace retrace::bench {

void AddCalibrateLidarOptions(CLI::App* cmd, CalibrateLidarOptions* options) {
  LidarCalibrationRequest& request = options->request;
  AddLogArgument(cmd, &request.log);
  cmd->add_option("--teach", request.teach_dir,
                  "The consistent teach folder of the same place (log-teach's consistent/teach)")
      ->required();
  AddOutOption(cmd, &request.out, "The YAML file to write (a sim.lidar.noise block)")->required();
  cmd->add_option("--figure", request.figure,
                  "The range error figure (PNG; default: --out with the extension .png)");
  AddNoFiguresFlag(cmd, &request.figures, "Do not render the figure");
  AddWindowOptions(cmd, &request.window);
  AddReferenceOption(cmd, &request.reference);
  cmd->add_flag("--synthetic-odometry", request.synthetic_odometry,
                "A corrected log's poses are the reference, as with log-teach "
                "--synthetic-odometry (the drawn odometry itself is not used)");
  cmd->add_option("--max-iterations", request.max_iterations,
                  "EM iterations allowed per fit (default 1000)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--min-beams", request.min_beams,
                  "Beams with an expected range the map knows needed in each half of the "
                  "window (default 1000)")
      ->check(CLI::Range(1, 1000000000));
  AddConfigOption(cmd, &request.config,
                  "Settings file (YAML), as for log-simulate: the clutter block's band, clearance "
                  "and kinds define where and what the density is measured as");
  AddSetOption(cmd, &request.overrides, "a setting, e.g. clutter.band=2");
  AddStreamOptions(cmd, &request.streams);
}

int RunCalibrateLidarCommand(const CalibrateLidarOptions& options,
                             const std::string& command_line) {
  const LidarCalibrationRun calibrated = CalibrateLidar(options.request);
  const std::vector<std::string> lines = WriteLidarCalibration(calibrated, command_line);
  std::cout << LidarCalibrationSummary(calibrated) << "\n";
  for (const std::string& line : lines) std::cout << line << "\n";
  return 0;
}

}  // namespace retrace::bench
