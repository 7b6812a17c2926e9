#pragma once
// The options the log commands share (`retrace log-info`, `log-teach`, `log-localize`,
// `calibrate-lidar`): which topics of a log to read where it has several (logs/sensor_log.hpp),
// the part of the log to use and a reference file.

#include <filesystem>
#include <optional>
#include <string>

#include "bench/replay/log_teach.hpp"
#include "logs/sensor_log.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

/// Adds the required positional `log` (a CARMEN log, an MCAP or SQLite file, a rosbag2 folder).
void AddLogArgument(CLI::App* cmd, std::filesystem::path* log);

/// Adds --from and --to (s since the log's first scan).
void AddWindowOptions(CLI::App* cmd, LogWindow* window);

/// Adds --reference (a TUM file with a reference trajectory on the log's clock).
void AddReferenceOption(CLI::App* cmd, std::optional<std::filesystem::path>* reference);

/// Adds --scan-topic, --odometry-topic, --reference-topic, --odom-frame and --base-frame.
void AddStreamOptions(CLI::App* cmd, logs::StreamChoice* choice);

}  // namespace retrace::bench
