#include "bench/run/scenario_run.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <memory>

#include "bench/engine/mode_list.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/stack_registry.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/metrics/experiment.hpp"
#include "bench/metrics/metrics.hpp"
#include "bench/output/manifest.hpp"
#include "bench/output/render_results.hpp"
#include "bench/output/results_io.hpp"
#include "bench/output/staged_folder.hpp"
#include "bench/output/video_recorder.hpp"
#include "bench/replay/log_recorder.hpp"
#include "core/errors.hpp"

namespace retrace::bench {
namespace {

// --mode: modes (comma-separated on the command line) or `all`; none: the scenario's modes.
std::vector<MapMode> ResolveModes(const std::vector<std::string>& names,
                                  const std::vector<MapMode>& scenario_modes, RunPhases phases) {
  if (names.empty()) return scenario_modes;
  std::vector<MapMode> modes = ParseModeList(names, "--mode");
  if (phases == RunPhases::kPlaybackOnly && modes.size() > 1) {
    throw core::ConfigError("--mode", "a teach folder holds the maps of one mode; give that one");
  }
  return modes;
}

// One staged folder per mode: a video is written into it while its run drives.
using ModeFolders = std::map<MapMode, std::unique_ptr<StagedFolder>>;

// --video-run names a run that is played back, by a stack the video can look into (it shows its
// particles and maps: StackInsight).
void RequireVideoRunPlayed(const ScenarioRunRequest& request, int repeats,
                           const std::string& stack) {
  if (request.video && !FindStack(stack).insight) {
    throw core::ConfigError("--video", "the video shows the localizer's particles and maps, and "
                                       "playback.stack " + stack + " has none to show");
  }
  if (request.video && request.video_run >= repeats) {
    throw core::ConfigError("--video-run", "run " + std::to_string(request.video_run) +
                                               " is not played back (" + std::to_string(repeats) +
                                               " runs per mode)");
  }
}

// The logs are published as one folder: it must not be, or hold, a results folder.
void RequireLogFolderApart(const std::filesystem::path& record_log,
                           const std::filesystem::path& out) {
  const std::filesystem::path logs = std::filesystem::absolute(record_log).lexically_normal();
  const std::filesystem::path results = std::filesystem::absolute(out).lexically_normal();
  const auto [r, l] = std::mismatch(results.begin(), results.end(), logs.begin(), logs.end());
  if (r == results.end() || l == logs.end()) {
    throw core::ConfigError("--record-log", "must be a folder apart from the results folder " +
                                                out.string() + ", not it, in it or around it");
  }
}

// Reads a reused teach folder before anything is run or written; it must hold the teaching
// drive's truth.
ModeTeach ReadReusedTeach(const std::filesystem::path& teach_dir, MapMode mode) {
  ModeTeach teach = ReadTeachFolder(teach_dir, mode);
  if (teach.trace.X_WR.empty()) {
    throw core::IoError(teach_dir.string() +
                        ": no gt.tum (taught from a log without a reference): a simulated "
                        "playback measures against the teaching drive's truth; use "
                        "`retrace log-localize` for logs");
  }
  return teach;
}

// Stages the results folder's mode folders (an existing `out` must be a results folder).
ModeFolders StageModeFolders(const std::filesystem::path& out, const std::vector<MapMode>& modes) {
  ModeFolders folders;
  RequireFolderOrNothing(out);
  for (const MapMode mode : modes) {
    folders[mode] = std::make_unique<StagedFolder>(out / std::string(core::EnumName(mode)));
  }
  return folders;
}

// --video: a video recorder for run --video-run of each mode, in the mode's staged folder; a
// recorder that cannot start is a warning.
std::function<std::unique_ptr<PlaybackObserver>(const ModeTeach&, int)> VideoObserver(
    const ScenarioRunRequest& request, const ModeFolders& folders, double robot_radius,
    ProgressSink* progress) {
  VideoOptions video;
  video.speedup = request.video_speedup;
  return [&request, &folders, robot_radius, video, progress](
             const ModeTeach& teach, int run) -> std::unique_ptr<PlaybackObserver> {
    if (run != request.video_run) return nullptr;
    const std::string mode_name(core::EnumName(teach.mode));
    try {
      return std::make_unique<VideoRecorder>(
          folders.at(teach.mode)->path() / "runs" / std::to_string(run) / "video.mp4",
          mode_name + " maps, run " + std::to_string(run), robot_radius, video);
    } catch (const core::Error& e) {
      Warn(progress, "no video of " + mode_name + ": " + e.what());
      return nullptr;
    }
  };
}

// --record-log: every drive as a log in `folder`, the teaching drive's as teach.*.
std::function<std::unique_ptr<SensorTap>(const ModeTeach*, int)> LogTap(
    const StagedFolder& folder, const nav::RobotGeometry& robot) {
  return [&folder, &robot](const ModeTeach* teach, int run) -> std::unique_ptr<SensorTap> {
    if (teach == nullptr) return std::make_unique<LogRecorder>(folder.path(), "teach", robot);
    return std::make_unique<LogRecorder>(folder.path() / std::string(core::EnumName(teach->mode)),
                                         "run_" + std::to_string(run), robot);
  };
}

// The phases asked for: the playback runs of a reused teach folder, or the teaching drive and
// (unless teach only) the playback runs.
Experiment RunRequestedPhases(const Scenario& scenario, RunPhases phases,
                              std::vector<ModeTeach> reused, const ExperimentOptions& options) {
  if (phases == RunPhases::kPlaybackOnly) {
    const double teach_duration = reused.front().trace.time.back();
    return RunPlaybacks(scenario, std::move(reused), teach_duration, options);
  }
  return RunExperiment(scenario, scenario.config.modes, options);
}

// The scenario requires every run of `mode` to succeed (limits.success_required).
bool SuccessRequired(const ScenarioConfig& config, MapMode mode) {
  const std::vector<MapMode>& required = config.limits.success_required;
  return std::find(required.begin(), required.end(), mode) != required.end();
}

// One mode's files into its staged folder, which is then committed: the teach folder (unless
// reused), the runs, the metrics (when runs were played back) and the manifest. The mode's summary.
ModeSummary WriteModeFolder(StagedFolder& folder, const ModeResult& result,
                            const Scenario& scenario, RunPhases phases, int repeats,
                            ManifestInfo manifest) {
  const ModeTeach& teach = result.teach;
  if (phases != RunPhases::kPlaybackOnly) WriteTeachFolder(folder.path() / "teach", teach);
  for (const RunTrace& run : result.runs) {
    WriteRunFolder(folder.path() / "runs" / std::to_string(run.run), teach.trace, run,
                   scenario.config.metrics);
  }
  ModeSummary summary{teach.mode, 0, 0, {}};
  if (repeats > 0) {
    WriteModeMetrics(folder.path(), result);
    summary = SummarizeMode(teach.mode, result.aggregate);
  }
  manifest.mode = teach.mode;
  WriteManifest(folder.path() / "manifest.yaml", scenario, manifest);
  folder.Commit();
  return summary;
}

// Every mode's files into its staged folder, one folder after the other: each mode's summary
// into `done`, and exit code 1 when a mode that must succeed had a run that did not.
void WriteModeFolders(const ModeFolders& folders, const Experiment& experiment,
                      const Scenario& scenario, RunPhases phases, int repeats,
                      const ManifestInfo& manifest, ScenarioRun* done) {
  for (const ModeResult& result : experiment.modes) {
    StagedFolder& folder = *folders.at(result.teach.mode);
    const ModeSummary summary =
        WriteModeFolder(folder, result, scenario, phases, repeats, manifest);
    if (SuccessRequired(scenario.config, result.teach.mode) && summary.successes < summary.runs)
      done->exit_code = 1;
    done->modes.push_back(summary);
  }
}

// The scenario with the request's overrides and modes, and everything about the request that
// can be wrong, checked before anything is written.
struct Prepared {
  Scenario scenario;
  std::filesystem::path out;
  int repeats = 0;
  std::vector<ModeTeach> reused;  ///< kPlaybackOnly: the teach folder read back
};

Prepared Prepare(const ScenarioRunRequest& request, ProgressSink* progress) {
  const RunPhases phases = request.phases;
  Prepared p{LoadScenario(request.scenario,
                          CommandLineOverrides(request.overrides, request.seed, request.repeats)),
             {},
             0,
             {}};
  ScenarioConfig& config = p.scenario.config;
  config.modes = ResolveModes(request.modes, config.modes, phases);
  if (phases != RunPhases::kPlaybackOnly) RequireSwitchingModeIfOnline(p.scenario, config.modes);
  p.out = request.out.empty() ? std::filesystem::path("results") / config.name : request.out;
  for (const std::string& warning : p.scenario.warnings) Warn(progress, warning);
  p.repeats = phases == RunPhases::kTeachOnly ? 0 : config.playback.repeats;
  RequireVideoRunPlayed(request, p.repeats, config.playback.stack);
  if (!request.record_log.empty()) RequireLogFolderApart(request.record_log, p.out);
  if (phases == RunPhases::kPlaybackOnly)
    p.reused.push_back(ReadReusedTeach(request.teach_dir, config.modes.front()));
  return p;
}

}  // namespace

ScenarioRun RunScenario(const ScenarioRunRequest& request, const std::string& command_line,
                        ProgressSink* progress) {
  const auto wall_start = std::chrono::steady_clock::now();
  Prepared p = Prepare(request, progress);
  const Scenario& scenario = p.scenario;
  const ModeFolders folders = StageModeFolders(p.out, scenario.config.modes);
  ExperimentOptions run_options = RunOptionsFor(p.repeats, request.jobs, progress);
  if (request.video)
    run_options.observe =
        VideoObserver(request, folders, scenario.config.sim.robot.radius, progress);
  std::unique_ptr<StagedFolder> log_folder;
  if (!request.record_log.empty()) {
    log_folder = std::make_unique<StagedFolder>(request.record_log);
    run_options.tap = LogTap(*log_folder, scenario.robot);
  }
  const Experiment experiment =
      RunRequestedPhases(scenario, request.phases, std::move(p.reused), run_options);

  // Metrics, then the files: one staged folder per mode.
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const ManifestInfo manifest{command_line, MapMode::kPartial, wall_time, request.teach_dir};
  ScenarioRun done;
  done.out = p.out;
  WriteModeFolders(folders, experiment, scenario, request.phases, p.repeats, manifest, &done);
  if (experiment.modes.size() > 1 && p.repeats > 0)
    WriteComparison(p.out / "comparison.json", experiment.modes);
  if (log_folder) log_folder->Commit();
  // Figures last: a rendering failure (no OSMesa context, say) leaves the numbers intact.
  if (request.figures)
    FinishOrWarn(
        "figures", "render", p.out, [&] { RenderResults(p.out); }, progress);
  const TeachSpeed teach_speed{experiment.teach_duration_s, experiment.teach_cpu_time_s};
  done.summary = SummaryText(scenario, done.modes, teach_speed, p.out, wall_time);
  return done;
}

std::string ScenarioRunSummary(const ScenarioRun& run) { return run.summary; }

}  // namespace retrace::bench
