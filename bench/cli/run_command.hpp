#pragma once
// `retrace run`, `retrace teach` and `retrace playback`: teaching drive, playback runs,
// metrics and result files for the map modes of a scenario.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace retrace::bench {

struct RunOptions {
  std::filesystem::path scenario;
  std::vector<std::string> modes;  ///< mode names, or {"all"}; empty: the scenario's `modes`
  std::optional<int> repeats;
  std::optional<std::uint64_t> seed;
  std::filesystem::path out;  ///< results folder; empty: results/<scenario name>
  std::vector<std::string> overrides;
  int jobs = 0;                     ///< worker threads; 0: one per core
  std::filesystem::path teach_dir;  ///< playback: a teach/ folder of an earlier run
  bool figures = true;              ///< render the figures at the end (bench/render_results)
  bool report = true;               ///< write report.html at the end (bench/output/html_report)
  bool video = false;               ///< record a video of playback run `video_run` of each mode
  int video_run = 0;
  double video_speedup = 10.0;  ///< seconds of the run per second of video
  /// Write every drive as a CARMEN log and an MCAP bag into this folder (empty: no logs).
  std::filesystem::path record_log;
};

enum class RunPhases { kAll, kTeachOnly, kPlaybackOnly };

/// Adds the options shared by run / teach / playback to a CLI11 subcommand.
void AddRunOptions(CLI::App* command, RunOptions* options, RunPhases phases);

/// Runs the command; prints the summary on stdout. Returns the exit code: 0, or 1 when a run of
/// a mode in limits.success_required failed. Throws core::Error on bad input, before anything
/// is written.
int RunRunCommand(const RunOptions& options, RunPhases phases, const std::string& command_line);

}  // namespace retrace::bench
