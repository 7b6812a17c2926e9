#pragma once
// `retrace log-info <log>`: prints bench/replay/log_description.hpp's DescribeLog of the log.

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

}  // namespace retrace::bench
