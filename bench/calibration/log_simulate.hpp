#pragma once
// `retrace log-simulate`: the simulator's realism, measured on a log (docs/DESIGN.md §10). The
// log's reference trajectory is driven again in a world made of the consistent map that
// log-teach built from that reference, and at every scan of the log the simulated LiDAR — the
// log's geometry (beams, angles, range limits, mount) and the simulator's noise model — takes a
// scan there. The result is the same log with simulated scans: same stamps, same odometry, same
// reference. Localizing both in the same maps (`retrace log-localize`) shows what the
// simulator's scans leave out.

#include <filesystem>
#include <functional>

#include "bench/engine/teach_drive.hpp"
#include "bench/replay/log_config.hpp"
#include "bench/replay/log_streams.hpp"
#include "bench/replay/log_teach.hpp"
#include "logs/sensor_log.hpp"

namespace retrace::bench {

struct LogSimulation {
  std::size_t scans = 0;  ///< simulated
  double first_stamp = 0.0;
  double last_stamp = 0.0;
};

/// Called per simulated scan: its stamp, the reference pose X_MR in the map's frame, the scan
/// (labelled with the log's angles).
using SimulatedScanSink =
    std::function<void(double stamp, const core::Pose2& X_MR, const core::LaserScan& scan)>;

/// Simulates the scans of `index` in `window` at the reference's poses in the world of
/// `world_teach` (as SimulateLog, without writing them); returns how many, and when.
LogSimulation SimulateScans(const logs::LogIndex& index, const LogStreams& streams,
                            const ModeTeach& world_teach,
                            const std::filesystem::path& world_teach_dir, const LogConfig& config,
                            const LogWindow& window, const SimulatedScanSink& sink);

/// Writes `out` (an MCAP file: /scan simulated, /odom the log's odometry, /ground_truth the
/// reference, /tf_static the mount) for the scans of `index` in `window`. `world_teach` is a
/// teach folder of one map built with a reference (log-teach's consistent mode): its map is the
/// world and its trace places the reference in it. Throws core::ConfigError("--teach", ...) for a
/// teach folder of several maps or without a reference, core::IoError for a log without
/// reference or a window without scans.
LogSimulation SimulateLog(const logs::LogIndex& index, const LogStreams& streams,
                          const ModeTeach& world_teach,
                          const std::filesystem::path& world_teach_dir, const LogConfig& config,
                          const LogWindow& window, const std::filesystem::path& out);

}  // namespace retrace::bench
