#pragma once
// `retrace log-teach`: the teaching drive of a recorded log (docs/DESIGN.md §10). The log's
// scans and odometry feed the same teach recorders as the simulator's teaching drive
// (bench/engine/teach_drive.hpp), one per map mode, with the same switching: online (the
// recorder decides), auto (from the driven path's geometry) or arc lengths along the driven
// path. The recorders get one pose per scan, the odometry interpolated at the scan's stamp.
// A reference, when there is one, gives the consistent mode and the traces that local truth is
// made of; the driven path is the reference's when there is one, else the odometry's.

#include <string>
#include <vector>

#include "bench/engine/teach_drive.hpp"
#include "bench/replay/log_config.hpp"
#include "bench/replay/log_streams.hpp"
#include "logs/sensor_log.hpp"

namespace retrace::bench {

/// The part of a log to use: log time in s since its first message.
struct LogWindow {
  double from_s = 0.0;
  double to_s = 1e300;
};

struct LogTeachResult {
  std::vector<ModeTeach> modes;       ///< in the order of LogTeachModes
  std::size_t scans = 0;              ///< scans taught with
  std::size_t scans_outside = 0;      ///< scans in the window without odometry or reference
  double first_s = 0.0;               ///< log time of the first scan used
  double last_s = 0.0;                ///< ... and of the last
  double driven_m = 0.0;              ///< length of the driven path
  std::vector<double> switch_points;  ///< auto or listed: the arc lengths used (m)
  double cpu_time_s = 0.0;
};

/// The modes log-teach builds: config.modes, or partial, scan_matched and (with a reference)
/// consistent. Throws core::ConfigError("modes", ...) for consistent without a reference, and
/// like RequireSwitchingModeIfOnline.
std::vector<MapMode> LogTeachModes(const LogConfig& config, const LogStreams& streams);

/// Teaches with the scans of `index` in `window`. Throws core::IoError for a window that holds
/// no scan with odometry, core::ConfigError for switch points beyond the driven path, and like
/// logs::ReadScans.
LogTeachResult RunLogTeach(const logs::LogIndex& index, const LogStreams& streams,
                           const LogConfig& config, const LogWindow& window);

}  // namespace retrace::bench
