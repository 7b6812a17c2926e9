#include "bench/cli/run_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/experiment_setup.hpp"
#include "bench/cli/mode_list.hpp"
#include "bench/cli/progress.hpp"
#include "bench/cli/report_command.hpp"
#include "bench/cli/shared_options.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/metrics/experiment.hpp"
#include "bench/metrics/metrics.hpp"
#include "bench/output/manifest.hpp"
#include "bench/output/render_results.hpp"
#include "bench/output/results_io.hpp"
#include "bench/output/staged_folder.hpp"
#include "bench/output/summary.hpp"
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

// --video-run names a run that is played back.
void RequireVideoRunPlayed(const RunOptions& options, int repeats) {
  if (options.video && options.video_run >= repeats) {
    throw core::ConfigError("--video-run", "run " + std::to_string(options.video_run) +
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
    const RunOptions& options, const ModeFolders& folders, double robot_radius) {
  VideoOptions video;
  video.speedup = options.video_speedup;
  return [&options, &folders, robot_radius, video](const ModeTeach& teach,
                                                   int run) -> std::unique_ptr<PlaybackObserver> {
    if (run != options.video_run) return nullptr;
    const std::string mode_name(core::EnumName(teach.mode));
    try {
      return std::make_unique<VideoRecorder>(
          folders.at(teach.mode)->path() / "runs" / std::to_string(run) / "video.mp4",
          mode_name + " maps, run " + std::to_string(run), robot_radius, video);
    } catch (const core::Error& e) {
      std::cerr << "retrace: warning: no video of " << mode_name << ": " << e.what() << "\n";
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

// What the mode folders hold in short: each mode's summary, and exit code 1 when a mode that
// must succeed had a run that did not.
struct ModesWritten {
  std::vector<ModeSummary> summaries;
  int exit_code = 0;
};

// Every mode's files into its staged folder, one folder after the other.
ModesWritten WriteModeFolders(const ModeFolders& folders, const Experiment& experiment,
                              const Scenario& scenario, RunPhases phases, int repeats,
                              const ManifestInfo& manifest) {
  ModesWritten written;
  for (const ModeResult& result : experiment.modes) {
    StagedFolder& folder = *folders.at(result.teach.mode);
    const ModeSummary summary =
        WriteModeFolder(folder, result, scenario, phases, repeats, manifest);
    if (SuccessRequired(scenario.config, result.teach.mode) && summary.successes < summary.runs)
      written.exit_code = 1;
    written.summaries.push_back(summary);
  }
  return written;
}

}  // namespace

void AddRunOptions(CLI::App* command, RunOptions* options, RunPhases phases) {
  command->add_option("scenario", options->scenario, "Scenario file (YAML)")->required();
  if (phases == RunPhases::kPlaybackOnly) {
    command
        ->add_option("--teach", options->teach_dir, "The teach/ folder of an earlier run or teach")
        ->required();
    command
        ->add_option(
            "--mode", options->modes,
            "Map mode the teach folder was built in (partial|single|consistent|scan_matched)")
        ->delimiter(',')
        ->default_val("partial");
  } else {
    command
        ->add_option(
            "--mode", options->modes,
            "Map modes: partial|single|consistent|scan_matched, comma-separated, or all (default: "
            "the scenario's modes)")
        ->delimiter(',');
  }
  if (phases != RunPhases::kTeachOnly) {
    command->add_option("--repeats", options->repeats, "Playback runs per mode")->check(kPositive);
    AddJobsOption(command, &options->jobs);
  }
  AddSeedOption(command, &options->seed, "of the scenario (overrides the file's)");
  AddOutOption(command, &options->out, "Results folder (default: results/<scenario name>)");
  AddSetOption(command, &options->overrides, "a scenario key: a.b.c=value");
  if (phases != RunPhases::kPlaybackOnly) {
    command->add_option("--record-log", options->record_log,
                        "Also write every drive as a CARMEN log and an MCAP bag into this folder: "
                        "teach.log.gz, teach.mcap, <mode>/run_<i>.log.gz, <mode>/run_<i>.mcap");
  }
  if (phases != RunPhases::kTeachOnly) {
    AddNoFiguresFlag(command, &options->figures,
                     "Do not render the figures (retrace render does it later)");
    AddNoReportFlag(command, &options->report,
                    "Do not write report.html, the results folder's page of tables, figures "
                    "and manifests (retrace report does it later)");
    command->add_flag("--video", options->video,
                      "Record a video of one playback run per mode: <mode>/runs/<run>/video.mp4");
    command->add_option("--video-run", options->video_run, "The run to record (default 0)")
        ->check(kNonNegative);
    command
        ->add_option("--video-speed", options->video_speedup,
                     "Seconds of the run per second of video (default 10)")
        ->check(kPositive);
  }
}

int RunRunCommand(const RunOptions& options, RunPhases phases, const std::string& command_line) {
  const auto wall_start = std::chrono::steady_clock::now();
  Scenario scenario = LoadScenario(
      options.scenario, CommandLineOverrides(options.overrides, options.seed, options.repeats));
  ScenarioConfig& config = scenario.config;
  config.modes = ResolveModes(options.modes, config.modes, phases);
  if (phases != RunPhases::kPlaybackOnly) RequireSwitchingModeIfOnline(scenario, config.modes);
  const std::filesystem::path out =
      options.out.empty() ? std::filesystem::path("results") / config.name : options.out;
  PrintScenarioWarnings(scenario);
  const int repeats = phases == RunPhases::kTeachOnly ? 0 : config.playback.repeats;
  RequireVideoRunPlayed(options, repeats);
  if (!options.record_log.empty()) RequireLogFolderApart(options.record_log, out);
  std::vector<ModeTeach> reused;
  if (phases == RunPhases::kPlaybackOnly)
    reused.push_back(ReadReusedTeach(options.teach_dir, config.modes.front()));

  const ModeFolders folders = StageModeFolders(out, config.modes);
  ProgressLine progress;
  ExperimentOptions run_options = CommandExperimentOptions(repeats, options.jobs, &progress);
  if (options.video) run_options.observe = VideoObserver(options, folders, config.sim.robot.radius);
  std::unique_ptr<StagedFolder> log_folder;
  if (!options.record_log.empty()) {
    log_folder = std::make_unique<StagedFolder>(options.record_log);
    run_options.tap = LogTap(*log_folder, scenario.robot);
  }
  const Experiment experiment =
      RunRequestedPhases(scenario, phases, std::move(reused), run_options);
  progress.Clear();

  // Metrics, then the files: one staged folder per mode.
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  ManifestInfo manifest;
  manifest.command_line = command_line;
  manifest.wall_time_s = wall_time;
  manifest.teach_dir = options.teach_dir;
  const ModesWritten written =
      WriteModeFolders(folders, experiment, scenario, phases, repeats, manifest);
  if (experiment.modes.size() > 1 && repeats > 0)
    WriteComparison(out / "comparison.json", experiment.modes);
  if (log_folder) log_folder->Commit();
  // Figures last: a rendering failure (no OSMesa context, say) leaves the numbers intact.
  if (options.figures) FinishOrWarn("figures", "render", out, [&] { RenderResults(out); });

  const TeachSpeed teach_speed{experiment.teach_duration_s, experiment.teach_cpu_time_s};
  std::cout << SummaryText(scenario, written.summaries, teach_speed, out, wall_time);
  if (options.report && phases != RunPhases::kTeachOnly) WriteReportAtEnd(out);
  return written.exit_code;
}

}  // namespace retrace::bench
