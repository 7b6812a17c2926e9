#pragma once
// `retrace log-compare` as one library call: read several log-localize folders (CompareLogs,
// bench/calibration/log_comparison.hpp), write their table and the figure of their errors into
// a results folder (WriteLogCompareFolder), and say what was compared (LogCompareSummary). The
// command line and the Python module call these.

#include <filesystem>
#include <string>
#include <vector>

#include "bench/calibration/log_comparison.hpp"

namespace retrace::bench {

struct LogCompareRequest {
  std::vector<std::filesystem::path> runs;  ///< log-localize folders, two or more
  std::vector<std::string> labels;          ///< their names (empty: the folders' names)
  std::filesystem::path out;                ///< the folder to write
};

/// The runs read back, with what their folder and summary are made of.
struct LogComparison {
  LogCompareRequest request;
  std::vector<LoggedRun> runs;
};

/// Reads the folders. Throws core::ConfigError("runs", ...) for fewer than two, and like
/// ReadLoggedRuns, before anything is written.
LogComparison CompareLogs(const LogCompareRequest& request);

/// Writes request.out (staged, renamed when complete): comparison.md and errors.png. Returns
/// notes on what was not written: a figure that cannot be rendered is a note, not an error.
std::vector<std::string> WriteLogCompareFolder(const LogComparison& compared);

/// The table and the results folder as the command line prints them, with the notes
/// WriteLogCompareFolder returned (several lines, no trailing newline).
std::string LogCompareSummary(const LogComparison& compared, const std::vector<std::string>& notes);

}  // namespace retrace::bench
