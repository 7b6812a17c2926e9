#pragma once
// The options every log command shares (`retrace log-info`, `log-teach`, `log-localize`): which
// topics of a log to read where it has several (logs/sensor_log.hpp).

#include <filesystem>
#include <string>

#include "logs/sensor_log.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

/// `v` with `digits` digits after the point ("12.30"), for the log commands' summaries.
std::string FixedText(double v, int digits);

/// Adds the required positional `log` (a CARMEN log, an MCAP or SQLite file, a rosbag2 folder).
void AddLogArgument(CLI::App* cmd, std::filesystem::path* log);

/// Adds --scan-topic, --odometry-topic, --reference-topic, --odom-frame and --base-frame.
void AddStreamOptions(CLI::App* cmd, logs::StreamChoice* choice);

}  // namespace retrace::bench
