#include "bench/cli/run_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/mode_list.hpp"
#include "bench/cli/progress.hpp"
#include "bench/cli/report_command.hpp"
#include "bench/engine/parallel.hpp"
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
#include "io/config_override.hpp"

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
    command->add_option("--jobs", options->jobs, "Worker threads (default: one per core)")
        ->check(kNonNegative);
  }
  command->add_option("--seed", options->seed, "Scenario seed (overrides the file's)")
      ->check(kSeed);
  command->add_option("--out", options->out, "Results folder (default: results/<scenario name>)");
  command->add_option("--set", options->overrides,
                      "Override a scenario key: a.b.c=value (repeatable)");
  if (phases != RunPhases::kPlaybackOnly) {
    command->add_option("--record-log", options->record_log,
                        "Also write every drive as a CARMEN log and an MCAP bag into this folder: "
                        "teach.log.gz, teach.mcap, <mode>/run_<i>.log.gz, <mode>/run_<i>.mcap");
  }
  if (phases != RunPhases::kTeachOnly) {
    command->add_flag("!--no-figures", options->figures,
                      "Do not render the figures (retrace render does it later)");
    command->add_flag("!--no-report", options->report,
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
  std::vector<io::ConfigOverride> overrides;
  for (const std::string& text : options.overrides) overrides.push_back(io::ParseOverride(text));
  if (options.seed) overrides.push_back(io::ParseOverride("seed=" + std::to_string(*options.seed)));
  if (options.repeats)
    overrides.push_back(io::ParseOverride("playback.repeats=" + std::to_string(*options.repeats)));
  Scenario scenario = LoadScenario(options.scenario, overrides);
  ScenarioConfig& config = scenario.config;
  config.modes = ResolveModes(options.modes, config.modes, phases);
  if (phases != RunPhases::kPlaybackOnly) RequireSwitchingModeIfOnline(scenario, config.modes);
  const std::filesystem::path out =
      options.out.empty() ? std::filesystem::path("results") / config.name : options.out;
  for (const std::string& warning : scenario.warnings)
    std::cerr << "retrace: warning: " << warning << "\n";

  const int repeats = phases == RunPhases::kTeachOnly ? 0 : config.playback.repeats;
  if (options.video && options.video_run >= repeats) {
    throw core::ConfigError("--video-run", "run " + std::to_string(options.video_run) +
                                               " is not played back (" + std::to_string(repeats) +
                                               " runs per mode)");
  }

  if (!options.record_log.empty()) {
    // The logs are published as one folder: it must not be, or hold, a results folder.
    const std::filesystem::path logs =
        std::filesystem::absolute(options.record_log).lexically_normal();
    const std::filesystem::path results = std::filesystem::absolute(out).lexically_normal();
    const auto [r, l] = std::mismatch(results.begin(), results.end(), logs.begin(), logs.end());
    if (r == results.end() || l == logs.end()) {
      throw core::ConfigError("--record-log", "must be a folder apart from the results folder " +
                                                  out.string() + ", not it, in it or around it");
    }
  }

  // Read a reused teach folder before anything is run or written.
  std::vector<ModeTeach> reused;
  if (phases == RunPhases::kPlaybackOnly) {
    reused.push_back(ReadTeachFolder(options.teach_dir, config.modes.front()));
    if (reused.back().trace.X_WR.empty()) {
      throw core::IoError(options.teach_dir.string() +
                          ": no gt.tum (taught from a log without a reference): a simulated "
                          "playback measures against the teaching drive's truth; use "
                          "`retrace log-localize` for logs");
    }
  }

  // One staged folder per mode: a video is written into it while its run drives.
  std::map<MapMode, std::unique_ptr<StagedFolder>> folders;
  RequireFolderOrNothing(out);
  for (const MapMode mode : config.modes) {
    folders[mode] = std::make_unique<StagedFolder>(out / std::string(core::EnumName(mode)));
  }

  ProgressLine progress;
  ExperimentOptions run_options;
  run_options.repeats = repeats;
  run_options.jobs = options.jobs > 0 ? options.jobs : DefaultJobs();
  run_options.progress = &progress;
  if (options.video) {
    VideoOptions video;
    video.speedup = options.video_speedup;
    run_options.observe = [&](const ModeTeach& teach,
                              int run) -> std::unique_ptr<PlaybackObserver> {
      if (run != options.video_run) return nullptr;
      const std::string mode_name(core::EnumName(teach.mode));
      try {
        return std::make_unique<VideoRecorder>(
            folders.at(teach.mode)->path() / "runs" / std::to_string(run) / "video.mp4",
            mode_name + " maps, run " + std::to_string(run), config.sim.robot.radius, video);
      } catch (const core::Error& e) {
        std::cerr << "retrace: warning: no video of " << mode_name << ": " << e.what() << "\n";
        return nullptr;
      }
    };
  }
  std::unique_ptr<StagedFolder> log_folder;
  if (!options.record_log.empty()) {
    log_folder = std::make_unique<StagedFolder>(options.record_log);
    run_options.tap = [&](const ModeTeach* teach, int run) -> std::unique_ptr<SensorTap> {
      if (teach == nullptr)
        return std::make_unique<LogRecorder>(log_folder->path(), "teach", scenario.robot);
      return std::make_unique<LogRecorder>(
          log_folder->path() / std::string(core::EnumName(teach->mode)),
          "run_" + std::to_string(run), scenario.robot);
    };
  }
  Experiment experiment;
  if (phases == RunPhases::kPlaybackOnly) {
    const double teach_duration = reused.front().trace.time.back();
    experiment = RunPlaybacks(scenario, std::move(reused), teach_duration, run_options);
  } else {
    experiment = RunExperiment(scenario, config.modes, run_options);
  }
  progress.Clear();

  // Metrics, then the files: one staged folder per mode.
  int exit_code = 0;
  std::vector<ModeSummary> summaries;
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  for (const ModeResult& result : experiment.modes) {
    const ModeTeach& teach = result.teach;
    const std::vector<RunTrace>& runs = result.runs;
    StagedFolder& folder = *folders.at(teach.mode);
    if (phases != RunPhases::kPlaybackOnly) WriteTeachFolder(folder.path() / "teach", teach);
    for (const RunTrace& run : runs) {
      WriteRunFolder(folder.path() / "runs" / std::to_string(run.run), teach.trace, run,
                     config.metrics);
    }
    ModeSummary summary{teach.mode, 0, 0, {}};
    if (repeats > 0) {
      WriteModeMetrics(folder.path(), result);
      summary = SummarizeMode(teach.mode, result.aggregate);
      const bool required =
          std::find(config.limits.success_required.begin(), config.limits.success_required.end(),
                    teach.mode) != config.limits.success_required.end();
      if (required && summary.successes < summary.runs) exit_code = 1;
    }
    ManifestInfo info;
    info.command_line = command_line;
    info.mode = teach.mode;
    info.wall_time_s = wall_time;
    info.teach_dir = options.teach_dir;
    WriteManifest(folder.path() / "manifest.yaml", scenario, info);
    folder.Commit();
    summaries.push_back(summary);
  }
  if (experiment.modes.size() > 1 && repeats > 0)
    WriteComparison(out / "comparison.json", experiment.modes);
  if (log_folder) log_folder->Commit();

  // Figures last: a rendering failure (no OSMesa context, say) leaves the numbers intact.
  if (options.figures) {
    const auto warn = [&](const char* what) {
      std::cerr << "retrace: warning: no figures: " << what
                << " (the results are complete; retry with `retrace render " << out.string()
                << "`)\n";
    };
    try {
      RenderResults(out);
    } catch (const core::Error& e) {
      warn(e.what());
    } catch (const std::filesystem::filesystem_error& e) {  // e.g. a figures/ that is a file
      warn(e.what());
    }
  }

  const TeachSpeed teach_speed{experiment.teach_duration_s, experiment.teach_cpu_time_s};
  std::cout << SummaryText(scenario, summaries, teach_speed, out, wall_time);
  if (options.report && phases != RunPhases::kTeachOnly) WriteReportAtEnd(out);
  return exit_code;
}

}  // namespace retrace::bench
