#pragma once
// `retrace log-info <log>`: what a recorded log holds and what the log commands would take from
// it — messages per topic, duration, the scans' geometry, the odometry's path length, the LiDAR
// mount and whether a reference trajectory exists.

#include <filesystem>
#include <string>

#include "logs/sensor_log.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

struct LogInfoOptions {
  std::filesystem::path log;
  logs::StreamChoice streams;
};

void AddLogInfoOptions(CLI::App* cmd, LogInfoOptions* options);

/// Prints the description of the log (DescribeLog); returns 0. Throws core::IoError for a log
/// that cannot be read, and, after the description, for one the log commands cannot use
/// (logs/sensor_log.hpp, RequireUsable) — but not for one that only needs a topic chosen
/// (LogIndex::needs_choice): log-info describes them all.
int RunLogInfoCommand(const LogInfoOptions& options);

/// What the log holds, several lines: topics, every scan topic, odometry, mount, reference,
/// notes and, where a stream has several topics, the choice the other commands need.
std::string DescribeLog(const logs::LogIndex& index);

}  // namespace retrace::bench
