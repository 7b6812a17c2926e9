#pragma once
// `retrace run`, `retrace teach` and `retrace playback` as one library call (RunScenario): the
// scenario's teaching drive and playback runs in its map modes, written as a results folder
// (one staged folder per mode: teach/, runs/, metrics, manifest; comparison.json; figures), and
// what it measured (ScenarioRunSummary). The command line and the Python module call these.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/engine/progress.hpp"
#include "bench/output/summary.hpp"

namespace retrace::bench {

/// What is run: the teaching drive and the playback runs, the teaching drive only, or the
/// playback runs of a teach folder written earlier.
enum class RunPhases { kAll, kTeachOnly, kPlaybackOnly };

struct ScenarioRunRequest {
  std::filesystem::path scenario;
  RunPhases phases = RunPhases::kAll;
  std::vector<std::string> modes;  ///< mode names, or {"all"}; empty: the scenario's `modes`
  std::optional<int> repeats;
  std::optional<std::uint64_t> seed;
  std::filesystem::path out;           ///< results folder; empty: results/<scenario name>
  std::vector<std::string> overrides;  ///< a.b.c=value
  int jobs = 0;                        ///< worker threads; 0: one per core
  std::filesystem::path teach_dir;     ///< kPlaybackOnly: a teach/ folder of an earlier run
  bool figures = true;                 ///< render the figures at the end (bench/render_results)
  bool video = false;                  ///< record a video of playback run `video_run` of each mode
  int video_run = 0;
  double video_speedup = 10.0;  ///< seconds of the run per second of video
  /// Write every drive as a CARMEN log and an MCAP bag into this folder (empty: no logs).
  std::filesystem::path record_log;
};

/// A run done and its results folder written.
struct ScenarioRun {
  std::filesystem::path out;  ///< the results folder
  std::vector<ModeSummary> modes;
  /// 1 when a run of a mode in limits.success_required failed, else 0.
  int exit_code = 0;
  std::string summary;  ///< the summary table (SummaryText)
};

/// Runs the phases asked for and writes the results folder; `command_line` goes into the
/// manifests. Progress, the scenario's warnings and the figures or videos that could not be
/// made (not errors: the results are complete without them) go to `progress` (may be null).
/// Throws core::Error on bad input, before anything is written.
ScenarioRun RunScenario(const ScenarioRunRequest& request, const std::string& command_line,
                        ProgressSink* progress);

/// The run's summary as the command line prints it (several lines, each ending in a newline).
std::string ScenarioRunSummary(const ScenarioRun& run);

}  // namespace retrace::bench
