#pragma once
// What every log command reads: the log, its streams and window, the reference, the settings,
// and where the results go (the library form of the log commands' shared options).

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/replay/log_config.hpp"
#include "bench/replay/log_teach.hpp"
#include "logs/sensor_log.hpp"

namespace retrace::bench {

struct LogRunOptions {
  std::filesystem::path log;
  std::filesystem::path out;
  logs::StreamChoice streams;
  LogWindow window;
  bool synthetic_odometry = false;
  std::optional<std::filesystem::path> reference;  ///< TUM file
  std::optional<std::filesystem::path> config;     ///< --config FILE
  std::vector<std::string> overrides;              ///< --set key=value
  std::optional<std::uint64_t> seed;
  bool figures = true;
};

/// Throws core::ConfigError naming --from or --to unless 0 <= from < to.
void RequireWindow(const LogWindow& window);

/// The settings of a log command: the config file, then --set, the seed and `extra` overrides.
/// Checks the window first.
LogConfig LoadLogRunConfig(const LogRunOptions& options, const std::vector<std::string>& extra);

}  // namespace retrace::bench
