#pragma once
// `retrace calibrate-lidar` as one library call: fit the beam model's intrinsic parameters to a
// log's scans against the map of the same place, and the simulated world that reproduces what
// the map does not hold (CalibrateLidar, bench/calibration/lidar_calibration.hpp); write them as
// a `sim.lidar.noise` block that --config and a scenario take as it is, the fit report as
// comments, and the range error figure beside it (WriteLidarCalibration); and say what was
// fitted (LidarCalibrationSummary). The command line and the Python module call these.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/calibration/lidar_calibration.hpp"
#include "bench/engine/clutter.hpp"
#include "bench/replay/log_teach.hpp"
#include "logs/sensor_log.hpp"
#include "sim/lidar.hpp"

namespace retrace::bench {

struct LidarCalibrationRequest {
  std::filesystem::path log;
  std::filesystem::path teach_dir;              ///< a consistent teach folder of the same place
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

/// A calibrated LiDAR, with everything its YAML file, figure and summary are made of.
struct LidarCalibrationRun {
  LidarCalibrationRequest request;
  std::string log_name;
  ClutterConfig clutter;
  LidarCalibration calibration;
  WorldInference world;
  sim::LidarNoiseConfig noise;      ///< WorldNoise of the whole window's mixture
  std::vector<std::string> report;  ///< the fit report, one line each
};

/// Reads the teach folder and the log, fits the window and its halves and infers the simulated
/// world. Throws core::Error for bad input (a teach folder that is not a consistent one, a log
/// without reference, too few beams the map knows, a fit that does not converge), one line
/// naming the file, option or key.
LidarCalibrationRun CalibrateLidar(const LidarCalibrationRequest& request);

/// Writes request.out atomically (the report as comments, then the sim.lidar.noise, unknown free
/// path and clutter settings), and with request.figures the figure (request.figure, else out's
/// .png). Returns the lines to print after the summary: the figure's path, or why it was not
/// rendered (not an error).
std::vector<std::string> WriteLidarCalibration(const LidarCalibrationRun& calibrated,
                                               const std::string& command_line);

/// The fit report and the YAML file's path as the command line prints them (several lines, no
/// trailing newline).
std::string LidarCalibrationSummary(const LidarCalibrationRun& calibrated);

}  // namespace retrace::bench
