#include "bench/cli/run_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/progress.hpp"
#include "bench/cli/report_command.hpp"
#include "bench/cli/shared_options.hpp"

namespace retrace::bench {

void AddRunOptions(CLI::App* command, RunOptions* options, RunPhases phases) {
  ScenarioRunRequest& request = options->request;
  command->add_option("scenario", request.scenario, "Scenario file (YAML)")->required();
  if (phases == RunPhases::kPlaybackOnly) {
    command
        ->add_option("--teach", request.teach_dir, "The teach/ folder of an earlier run or teach")
        ->required();
    command
        ->add_option(
            "--mode", request.modes,
            "Map mode the teach folder was built in (partial|single|consistent|scan_matched)")
        ->delimiter(',')
        ->default_val("partial");
  } else {
    command
        ->add_option(
            "--mode", request.modes,
            "Map modes: partial|single|consistent|scan_matched, comma-separated, or all (default: "
            "the scenario's modes)")
        ->delimiter(',');
  }
  if (phases != RunPhases::kTeachOnly) {
    command->add_option("--repeats", request.repeats, "Playback runs per mode")->check(kPositive);
    AddJobsOption(command, &request.jobs);
  }
  AddSeedOption(command, &request.seed, "of the scenario (overrides the file's)");
  AddOutOption(command, &request.out, "Results folder (default: results/<scenario name>)");
  AddSetOption(command, &request.overrides, "a scenario key: a.b.c=value");
  if (phases != RunPhases::kPlaybackOnly) {
    command->add_option("--record-log", request.record_log,
                        "Also write every drive as a CARMEN log, an MCAP file and a ROS 1 bag into "
                        "this folder: teach.log.gz, teach.mcap, teach.bag, "
                        "<mode>/run_<i>.{log.gz,mcap,bag}");
  }
  if (phases != RunPhases::kTeachOnly) {
    AddNoFiguresFlag(command, &request.figures,
                     "Do not render the figures (retrace render does it later)");
    AddNoReportFlag(command, &options->report,
                    "Do not write report.html, the results folder's page of tables, figures "
                    "and manifests (retrace report does it later)");
    command->add_flag("--video", request.video,
                      "Record a video of one playback run per mode: <mode>/runs/<run>/video.mp4");
    command->add_option("--video-run", request.video_run, "The run to record (default 0)")
        ->check(kNonNegative);
    command
        ->add_option("--video-speed", request.video_speedup,
                     "Seconds of the run per second of video (default 10)")
        ->check(kPositive);
  }
}

int RunRunCommand(const RunOptions& options, RunPhases phases, const std::string& command_line) {
  ScenarioRunRequest request = options.request;
  request.phases = phases;
  ScenarioRun run;
  {
    ProgressLine progress;
    run = RunScenario(request, command_line, &progress);
  }
  std::cout << ScenarioRunSummary(run);
  if (options.report && phases != RunPhases::kTeachOnly) WriteReportAtEnd(run.out);
  return run.exit_code;
}

}  // namespace retrace::bench
