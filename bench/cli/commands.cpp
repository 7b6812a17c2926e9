#include "bench/cli/commands.hpp"

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "bench/cli/bench_command.hpp"
#include "bench/cli/calibrate_lidar_command.hpp"
#include "bench/cli/campus_command.hpp"
#include "bench/cli/compare_command.hpp"
#include "bench/cli/crowd_check_command.hpp"
#include "bench/cli/log_compare_command.hpp"
#include "bench/cli/log_info_command.hpp"
#include "bench/cli/log_localize_command.hpp"
#include "bench/cli/log_simulate_command.hpp"
#include "bench/cli/log_teach_command.hpp"
#include "bench/cli/merge_command.hpp"
#include "bench/cli/report_command.hpp"
#include "bench/cli/run_command.hpp"
#include "bench/cli/sweep_command.hpp"
#include "bench/cli/tour_command.hpp"
#include "bench/cli/world_command.hpp"

namespace retrace::bench {
namespace {

// The runner of a command whose options `add` declares and `run` reads: the options live as
// long as the runner.
template <class Options, class Run>
CommandRunner Declare(CLI::App* command, void (*add)(CLI::App*, Options*), Run run) {
  auto options = std::make_shared<Options>();
  add(command, options.get());
  return [options, run](const std::string& command_line) { return run(*options, command_line); };
}

// A command that prints one summary line and succeeds.
template <class Options>
CommandRunner DeclarePrinting(CLI::App* command, void (*add)(CLI::App*, Options*),
                              std::string (*run)(const Options&)) {
  return Declare(command, add, [run](const Options& options, const std::string&) {
    std::cout << run(options) << "\n";
    return 0;
  });
}

// A command that does not record its command line.
template <class Options>
CommandRunner DeclareQuiet(CLI::App* command, void (*add)(CLI::App*, Options*),
                           int (*run)(const Options&)) {
  return Declare(command, add,
                 [run](const Options& options, const std::string&) { return run(options); });
}

// `run`, `teach` and `playback`: the same options but for each phase's own.
template <RunPhases kPhases>
CommandRunner DeclareRun(CLI::App* command) {
  auto options = std::make_shared<RunOptions>();
  AddRunOptions(command, options.get(), kPhases);
  return [options](const std::string& command_line) {
    return RunRunCommand(*options, kPhases, command_line);
  };
}

constexpr CommandSpec kCommands[] = {
    {"run",
     "Teach the scenario's route, play it back in each map mode, write metrics and trajectories",
     DeclareRun<RunPhases::kAll>},
    {"teach", "Drive the route once and write the teach bundles only",
     DeclareRun<RunPhases::kTeachOnly>},
    {"playback", "Play back a teach folder written by an earlier run or teach",
     DeclareRun<RunPhases::kPlaybackOnly>},
    {"world", "Load and check a world file, render it to a PNG",
     [](CLI::App* c) { return DeclarePrinting(c, AddWorldOptions, RenderWorldFile); }},
    {"render", "Render the figures of a results folder again, without rerunning",
     [](CLI::App* c) { return DeclareQuiet(c, AddRenderOptions, RunRenderCommand); }},
    {"report",
     "Write <dir>/report.html: one self-contained page of a results folder's tables, figures, "
     "comparison, regressions and manifests",
     [](CLI::App* c) { return DeclareQuiet(c, AddReportOptions, RunReportCommand); }},
    {"generate-campus",
     "Turn a route into a campus world: buildings, hedges, trees, poles, benches, pedestrians",
     [](CLI::App* c) { return DeclarePrinting(c, AddGenerateCampusOptions, GenerateCampusWorld); }},
    {"generate-tour",
     "Write a random looped tour, a campus world round it and a scenario that drives it",
     [](CLI::App* c) { return DeclarePrinting(c, AddGenerateTourOptions, GenerateTourFolder); }},
    {"compare",
     "Compare map modes over several seeds: paired differences with 95% confidence intervals",
     [](CLI::App* c) { return Declare(c, AddCompareOptions, RunCompareCommand); }},
    {"bench",
     "Run a regression suite and compare its metrics with the committed baseline (exit 1 on a "
     "regression)",
     [](CLI::App* c) { return DeclareQuiet(c, AddBenchOptions, RunBenchCommand); }},
    {"sweep",
     "Run a parameter sweep: every case of a sweep file, in parallel, resumable, in shards",
     [](CLI::App* c) { return Declare(c, AddSweepOptions, RunSweepCommand); }},
    {"merge", "Join the results folders of a sweep's shards into one",
     [](CLI::App* c) { return Declare(c, AddMergeOptions, RunMergeCommand); }},
    {"log-info",
     "Describe a recorded log (CARMEN, MCAP, rosbag2, ROS 1 bag): topics, scans, odometry, "
     "reference",
     [](CLI::App* c) { return DeclareQuiet(c, AddLogInfoOptions, RunLogInfoCommand); }},
    {"log-teach", "Build the teach folders (partial maps, paths) of a recorded log's drive",
     [](CLI::App* c) { return Declare(c, AddLogTeachOptions, RunLogTeachCommand); }},
    {"log-localize",
     "Localize a recorded log in a teach folder's partial maps, measured against its reference",
     [](CLI::App* c) { return Declare(c, AddLogLocalizeOptions, RunLogLocalizeCommand); }},
    {"log-simulate",
     "Drive a log's reference again in the simulator, in its consistent map, with its LiDAR: "
     "the same log with simulated scans",
     [](CLI::App* c) { return DeclareQuiet(c, AddLogSimulateOptions, RunLogSimulateCommand); }},
    {"log-compare", "Put log-localize results side by side: one table, one figure of errors",
     [](CLI::App* c) { return DeclareQuiet(c, AddLogCompareOptions, RunLogCompareCommand); }},
    {"calibrate-lidar",
     "Fit the beam model's noise (hit, short, max, random) to a log's scans against its "
     "consistent map: a sim.lidar.noise block",
     [](CLI::App* c) { return Declare(c, AddCalibrateLidarOptions, RunCalibrateLidarCommand); }},
    {"crowd-check",
     "Check the pedestrian crowd against Weidmann's speed-density curve (fundamental diagram)",
     [](CLI::App* c) { return DeclareQuiet(c, AddCrowdCheckOptions, RunCrowdCheckCommand); }},
};

}  // namespace

std::span<const CommandSpec> Commands() { return kCommands; }

}  // namespace retrace::bench
