#pragma once
// What a recorded log holds and what the log commands would take from it (`retrace log-info`):
// messages per topic, duration, the scans' geometry, the odometry's path length, the LiDAR mount
// and whether a reference trajectory exists.

#include <string>

#include "logs/sensor_log.hpp"

namespace retrace::bench {

/// What the log holds, several lines: topics, every scan topic, odometry, mount, reference,
/// notes and, where a stream has several topics, the choice the other commands need.
std::string DescribeLog(const logs::LogIndex& index);

}  // namespace retrace::bench
