#pragma once
// `retrace calibrate-lidar <log> --teach <consistent teach DIR> --out FILE.yaml`: the options of
// bench/calibration/lidar_calibration_run.hpp's CalibrateLidar, which it calls; writes the
// `sim.lidar.noise` block (FILE.yaml) and the range error figure (FILE.png) with
// WriteLidarCalibration and prints its summary.

#include <string>

#include "bench/calibration/lidar_calibration_run.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

struct CalibrateLidarOptions {
  LidarCalibrationRequest request;
};

void AddCalibrateLidarOptions(CLI::App* cmd, CalibrateLidarOptions* options);

/// Runs calibrate-lidar; returns 0. Throws core::Error for bad input (a teach folder that is not
/// a consistent one, a log without reference, too few beams the map knows, a fit that does not
/// converge) before anything is written; the YAML is written atomically.
int RunCalibrateLidarCommand(const CalibrateLidarOptions& options, const std::string& command_line);

}  // namespace retrace::bench
