#pragma once
// `retrace log-localize` as one library call: localize a recorded log in a teach folder's maps
// (LocalizeLog), then write its results folder (WriteLogLocalizeFolder, docs/FORMATS.md) and
// say what it measured (LogLocalizeSummary). The command line and the Python module call these.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/engine/teach_drive.hpp"
#include "bench/replay/log_config.hpp"
#include "bench/replay/log_localize.hpp"
#include "bench/replay/log_metrics.hpp"
#include "bench/replay/log_run_options.hpp"
#include "bench/replay/log_streams.hpp"
#include "logs/sensor_log.hpp"

namespace retrace::bench {

struct LogLocalizeRequest {
  LogRunOptions run;
  std::filesystem::path teach_dir;  ///< a teach/ folder (<mode>/teach of log-teach or run)
  /// Where the robot starts, in map 0's frame (none: the map nearest the reference, or map 0's
  /// origin without one).
  std::optional<core::Pose2> initial;
  bool every_odometry_tick = false;  ///< one prediction per odometry message
};

/// A localized log, with everything its results folder and summary are made of.
struct LogLocalization {
  LogLocalizeRequest request;  ///< what was asked (its run.out is where the folder goes)
  logs::LogIndex index;
  LogStreams streams;
  LogConfig config;
  ModeTeach teach;
  LogLocalizeResult run;
  LogLocalizeSeries series;
  LogLocalizeMetrics metrics;
};

/// Reads the teach folder and the log, and localizes the log's window in the teach folder's maps.
/// Throws core::Error on bad input (one line naming the file, option or key).
LogLocalization LocalizeLog(const LogLocalizeRequest& request);

/// Writes the results folder request.run.out (staged, renamed when complete): est_map.csv,
/// errors.csv, updates.csv, events.csv, est.tum and reference.tum, snapshot.json, metrics.json
/// and manifest.yaml, and with request.run.figures the figures. Returns the manifest's notes; a
/// figure that cannot be rendered adds a note and is not an error.
std::vector<std::string> WriteLogLocalizeFolder(const LogLocalization& localized,
                                                const std::string& command_line,
                                                double wall_time_s);

/// The run's summary as the command line prints it (several lines, no trailing newline).
std::string LogLocalizeSummary(const LogLocalization& localized);

}  // namespace retrace::bench
