#pragma once
// `retrace calibrate-lidar <log> --teach <consistent teach DIR> --out FILE.yaml`: the beam
// model's intrinsic parameters fitted to the log's scans against the map of the same place
// (bench/replay/lidar_calibration.hpp), written as a `sim.lidar.noise` block that --config and
// a scenario take as it is, the fits of the whole window and of its halves as comments; and the
// figure of the range errors against the fitted mixture beside it (FILE.png).

#include <cstddef>
#include <filesystem>
#include <optional>

#include "bench/replay/log_teach.hpp"
#include "logs/sensor_log.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

struct CalibrateLidarOptions {
  std::filesystem::path log;
  std::filesystem::path teach_dir;
  std::filesystem::path out;                    ///< the YAML file
  std::optional<std::filesystem::path> figure;  ///< default: `out` with the extension .png
  bool figures = true;
  logs::StreamChoice streams;
  LogWindow window;
  bool synthetic_odometry = false;  ///< a corrected log's poses are the reference
  std::optional<std::filesystem::path> reference;
  int max_iterations = 1000;
  std::size_t min_beams = 1000;  ///< per half of the window
  /// Settings as for log-simulate: its `clutter` block's band, corridor and kinds define the
  /// band the density is measured in.
  std::optional<std::filesystem::path> config;
  std::vector<std::string> overrides;
};

void AddCalibrateLidarOptions(CLI::App* cmd, CalibrateLidarOptions* options);

/// Runs calibrate-lidar; returns 0. Throws core::Error for bad input (a teach folder that is not
/// a consistent one, a log without reference, too few beams the map knows, a fit that does not
/// converge) before anything is written; the YAML is written atomically.
int RunCalibrateLidarCommand(const CalibrateLidarOptions& options, const std::string& command_line);

}  // namespace retrace::bench
