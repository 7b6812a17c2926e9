#pragma once
// `retrace log-compare`: several localization runs of logs (`retrace log-localize` folders) side by
// side — typically a log and the same log simulated (`retrace log-simulate`), or one log in the
// maps of several modes: one table of their metrics and one figure of their errors along the
// drive.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace retrace::bench {

/// One log-localize folder read back.
struct LoggedRun {
  std::string label;
  nlohmann::json metrics;        ///< its metrics.json
  std::vector<double> driven_m;  ///< errors.csv, per scan
  std::vector<double> path_distance_m;
  std::vector<double> localization_error_m;
};

/// Reads the folders; `labels` names them (empty: the folders' names). Throws core::IoError
/// naming the folder and file for a folder that is not a log-localize result,
/// core::ConfigError("--labels", ...) when the labels do not match the folders in number.
std::vector<LoggedRun> ReadLoggedRuns(const std::vector<std::filesystem::path>& dirs,
                                      const std::vector<std::string>& labels);

/// The table (Markdown): per run the scans, the localization error on the route and overall,
/// the lost and rejected fractions, the update time and the real-time factor.
std::string LoggedRunsTable(const std::vector<LoggedRun>& runs);

/// Writes `table` as comparison.md and the errors of every run against the distance driven as
/// errors.png into `dir` (which must exist); throws viz::RenderError when OSMesa cannot render.
void WriteLogComparison(const std::filesystem::path& dir, const std::vector<LoggedRun>& runs);

}  // namespace retrace::bench
