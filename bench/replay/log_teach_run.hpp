#pragma once
// `retrace log-teach` as one library call: teach a recorded log's drive in every map mode
// (TeachLog), then write its results folder, one teach folder and manifest per mode
// (WriteLogTeachFolder, docs/FORMATS.md), and say what it taught (LogTeachSummary). The command
// line and the Python module call these.

#include <filesystem>
#include <string>
#include <vector>

#include "bench/engine/trace.hpp"
#include "bench/replay/log_config.hpp"
#include "bench/replay/log_run_options.hpp"
#include "bench/replay/log_streams.hpp"
#include "bench/replay/log_teach.hpp"
#include "logs/sensor_log.hpp"

namespace retrace::bench {

struct LogTeachRequest {
  LogRunOptions run;
  /// Settings applied after run.overrides and the seed, e.g. the command's --switch-points as
  /// route.switch_points=auto|online|[s1,s2,...].
  std::vector<std::string> extra_overrides;
  std::vector<MapMode> modes;  ///< the modes to teach (empty: the config's, see LogTeachModes)
};

/// A taught log, with everything its results folder and summary are made of.
struct LogTeaching {
  LogTeachRequest request;  ///< what was asked (its run.out is where the folder goes)
  logs::LogIndex index;
  LogStreams streams;
  LogConfig config;  ///< with request.modes, when given, as its modes
  LogTeachResult result;
};

/// Reads the log and teaches its window in every mode. Throws core::Error on bad input (one line
/// naming the file, option or key), before anything is written.
LogTeaching TeachLog(const LogTeachRequest& request);

/// Writes the results folder request.run.out (staged, renamed when complete): per mode
/// <mode>/teach (the teach folder) and <mode>/manifest.yaml, and with request.run.figures
/// <mode>/figures/maps.png. Returns notes on what was not written: a figure that cannot be
/// rendered is a note, not an error.
std::vector<std::string> WriteLogTeachFolder(const LogTeaching& taught,
                                             const std::string& command_line, double wall_time_s);

/// The summary as the command line prints it (several lines, no trailing newline), with the
/// notes WriteLogTeachFolder returned among them.
std::string LogTeachSummary(const LogTeaching& taught, const std::vector<std::string>& notes);

}  // namespace retrace::bench
