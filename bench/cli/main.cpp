// The `retrace` command-line program. Exit codes: 0 success; 1 the runs completed but
// navigation failed where the scenario requires success; 2 bad input (one clear line on
// stderr, nothing written); 3 an internal error.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include "bench/cli/bench_command.hpp"
#include "bench/cli/calibrate_lidar_command.hpp"
#include "bench/cli/campus_command.hpp"
#include "bench/cli/cli_checks.hpp"
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
#include "bench/output/render_results.hpp"
#include "bench/suite/baseline.hpp"
#include "core/errors.hpp"

namespace {

namespace bench = retrace::bench;
namespace core = retrace::core;

constexpr int kExitBadInput = 2;
constexpr int kExitInternalError = 3;  // a bug in retrace, never bad input

std::string CommandLine(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) line += (i ? " " : "") + std::string(argv[i]);
  return line;
}

// Every subcommand with the options CLI11 fills when the command line names it.
struct Commands {
  bench::RunOptions run, teach, playback;
  CLI::App* run_cmd = nullptr;
  CLI::App* teach_cmd = nullptr;
  CLI::App* playback_cmd = nullptr;
  bench::WorldCommandOptions world;
  CLI::App* world_cmd = nullptr;
  std::filesystem::path render_dir;
  CLI::App* render_cmd = nullptr;
  bench::ReportOptions report;
  CLI::App* report_cmd = nullptr;
  bench::GenerateCampusOptions campus;
  CLI::App* campus_cmd = nullptr;
  bench::GenerateTourOptions tour;
  CLI::App* tour_cmd = nullptr;
  bench::CompareOptions compare;
  CLI::App* compare_cmd = nullptr;
  bench::BenchOptions bench_options;
  CLI::App* bench_cmd = nullptr;
  bench::SweepOptions sweep;
  CLI::App* sweep_cmd = nullptr;
  bench::MergeOptions merge;
  CLI::App* merge_cmd = nullptr;
  bench::LogInfoOptions log_info;
  CLI::App* log_info_cmd = nullptr;
  bench::LogTeachOptions log_teach;
  CLI::App* log_teach_cmd = nullptr;
  bench::LogLocalizeOptions log_localize;
  CLI::App* log_localize_cmd = nullptr;
  bench::LogSimulateOptions log_simulate;
  CLI::App* log_simulate_cmd = nullptr;
  bench::LogCompareOptions log_compare;
  CLI::App* log_compare_cmd = nullptr;
  bench::CalibrateLidarOptions calibrate_lidar;
  CLI::App* calibrate_lidar_cmd = nullptr;
  bench::CrowdCheckOptions crowd_check;
  CLI::App* crowd_check_cmd = nullptr;
};

// `run`, `teach` and `playback`: the whole experiment, or its teaching or playback phase.
void AddRunCommands(CLI::App& app, Commands& c) {
  c.run_cmd = app.add_subcommand(
      "run",
      "Teach the scenario's route, play it back in each map mode, write metrics and trajectories");
  bench::AddRunOptions(c.run_cmd, &c.run, bench::RunPhases::kAll);
  c.teach_cmd =
      app.add_subcommand("teach", "Drive the route once and write the teach bundles only");
  bench::AddRunOptions(c.teach_cmd, &c.teach, bench::RunPhases::kTeachOnly);
  c.playback_cmd =
      app.add_subcommand("playback", "Play back a teach folder written by an earlier run or teach");
  bench::AddRunOptions(c.playback_cmd, &c.playback, bench::RunPhases::kPlaybackOnly);
}

// `world`: load and check a world file, render it.
void AddWorldCommand(CLI::App& app, Commands& c) {
  bench::WorldCommandOptions& world = c.world;
  c.world_cmd = app.add_subcommand("world", "Load and check a world file, render it to a PNG");
  CLI::App* world_cmd = c.world_cmd;
  world_cmd->add_option("world", world.world_file, "World file (YAML)")->required();
  world_cmd->add_option("--png", world.png, "Output image")->required();
  world_cmd->add_option("--route", world.route_file,
                        "Route file to draw (x y per line or AutoNavi path)");
  world_cmd->add_option("--set", world.overrides, "Override a key: a.b.c=value (repeatable)");
  world_cmd
      ->add_option("--pixels-per-meter", world.pixels_per_meter,
                   "Image scale (default: 1600 px wide)")
      ->check(retrace::bench::kPositive);
  world_cmd->add_option("--seed", world.seed, "Seed for the pedestrians' spawn points")
      ->check(retrace::bench::kSeed);
}

// `render` and `report`: the figures and the page of a results folder, again.
void AddResultsCommands(CLI::App& app, Commands& c) {
  c.render_cmd = app.add_subcommand(
      "render", "Render the figures of a results folder again, without rerunning");
  c.render_cmd
      ->add_option("results", c.render_dir, "Results folder of `retrace run` (results/<scenario>)")
      ->required();
  c.report_cmd = app.add_subcommand(
      "report",
      "Write <dir>/report.html: one self-contained page of a results folder's tables, figures, "
      "comparison, regressions and manifests");
  bench::AddReportOptions(c.report_cmd, &c.report);
}

// `generate-campus` and `generate-tour`: worlds and scenarios written from a route.
void AddGenerateCommands(CLI::App& app, Commands& c) {
  c.campus_cmd = app.add_subcommand(
      "generate-campus",
      "Turn a route into a campus world: buildings, hedges, trees, poles, benches, pedestrians");
  bench::AddGenerateCampusOptions(c.campus_cmd, &c.campus);
  c.tour_cmd = app.add_subcommand(
      "generate-tour",
      "Write a random looped tour, a campus world round it and a scenario that drives it");
  bench::AddGenerateTourOptions(c.tour_cmd, &c.tour);
}

// `compare`, `bench`, `sweep` and `merge`: studies of many experiments.
void AddStudyCommands(CLI::App& app, Commands& c) {
  c.compare_cmd = app.add_subcommand(
      "compare",
      "Compare map modes over several seeds: paired differences with 95% confidence intervals");
  bench::AddCompareOptions(c.compare_cmd, &c.compare);
  c.bench_cmd = app.add_subcommand("bench",
                                   "Run a regression suite and compare its metrics with "
                                   "the committed baseline (exit 1 on a regression)");
  bench::AddBenchOptions(c.bench_cmd, &c.bench_options);
  c.sweep_cmd = app.add_subcommand(
      "sweep",
      "Run a parameter sweep: every case of a sweep file, in parallel, resumable, in shards");
  bench::AddSweepOptions(c.sweep_cmd, &c.sweep);
  c.merge_cmd =
      app.add_subcommand("merge", "Join the results folders of a sweep's shards into one");
  bench::AddMergeOptions(c.merge_cmd, &c.merge);
}

// `log-info`, `log-teach`, `log-localize`, `log-simulate`, `log-compare` and `calibrate-lidar`:
// recorded logs.
void AddLogCommands(CLI::App& app, Commands& c) {
  c.log_info_cmd = app.add_subcommand(
      "log-info",
      "Describe a recorded log (CARMEN, MCAP, rosbag2): topics, scans, odometry, reference");
  bench::AddLogInfoOptions(c.log_info_cmd, &c.log_info);
  c.log_teach_cmd = app.add_subcommand(
      "log-teach", "Build the teach folders (partial maps, paths) of a recorded log's drive");
  bench::AddLogTeachOptions(c.log_teach_cmd, &c.log_teach);
  c.log_localize_cmd = app.add_subcommand(
      "log-localize",
      "Localize a recorded log in a teach folder's partial maps, measured against its reference");
  bench::AddLogLocalizeOptions(c.log_localize_cmd, &c.log_localize);
  c.log_simulate_cmd = app.add_subcommand(
      "log-simulate",
      "Drive a log's reference again in the simulator, in its consistent map, with its LiDAR: "
      "the same log with simulated scans");
  bench::AddLogSimulateOptions(c.log_simulate_cmd, &c.log_simulate);
  c.log_compare_cmd = app.add_subcommand(
      "log-compare", "Put log-localize results side by side: one table, one figure of errors");
  bench::AddLogCompareOptions(c.log_compare_cmd, &c.log_compare);
  c.calibrate_lidar_cmd = app.add_subcommand(
      "calibrate-lidar",
      "Fit the beam model's noise (hit, short, max, random) to a log's scans against its "
      "consistent map: a sim.lidar.noise block");
  bench::AddCalibrateLidarOptions(c.calibrate_lidar_cmd, &c.calibrate_lidar);
}

// Every subcommand, in the order --help lists them.
void AddCommands(CLI::App& app, Commands& c) {
  AddRunCommands(app, c);
  AddWorldCommand(app, c);
  AddResultsCommands(app, c);
  AddGenerateCommands(app, c);
  AddStudyCommands(app, c);
  AddLogCommands(app, c);
  c.crowd_check_cmd = app.add_subcommand(
      "crowd-check",
      "Check the pedestrian crowd against Weidmann's speed-density curve (fundamental diagram)");
  bench::AddCrowdCheckOptions(c.crowd_check_cmd, &c.crowd_check);
}

// Parses the command line; an exit code when it asked for help or the version, or was bad.
std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "retrace: error: " << e.what() << " (see retrace --help)\n";
    return kExitBadInput;
  }
  return std::nullopt;
}

// Runs the subcommand the command line named; its exit code.
int RunNamedCommand(const Commands& c, const std::string& command_line) {
  if (*c.run_cmd) return bench::RunRunCommand(c.run, bench::RunPhases::kAll, command_line);
  if (*c.teach_cmd)
    return bench::RunRunCommand(c.teach, bench::RunPhases::kTeachOnly, command_line);
  if (*c.playback_cmd)
    return bench::RunRunCommand(c.playback, bench::RunPhases::kPlaybackOnly, command_line);
  if (*c.world_cmd) std::cout << bench::RunWorldCommand(c.world) << "\n";
  if (*c.campus_cmd) std::cout << bench::RunGenerateCampusCommand(c.campus) << "\n";
  if (*c.tour_cmd) std::cout << bench::RunGenerateTourCommand(c.tour) << "\n";
  if (*c.compare_cmd) return bench::RunCompareCommand(c.compare, command_line);
  if (*c.bench_cmd) return bench::RunBenchCommand(c.bench_options);
  if (*c.sweep_cmd) return bench::RunSweepCommand(c.sweep, command_line);
  if (*c.merge_cmd) return bench::RunMergeCommand(c.merge, command_line);
  if (*c.log_info_cmd) return bench::RunLogInfoCommand(c.log_info);
  if (*c.log_teach_cmd) return bench::RunLogTeachCommand(c.log_teach, command_line);
  if (*c.log_localize_cmd) return bench::RunLogLocalizeCommand(c.log_localize, command_line);
  if (*c.log_simulate_cmd) return bench::RunLogSimulateCommand(c.log_simulate);
  if (*c.log_compare_cmd) return bench::RunLogCompareCommand(c.log_compare);
  if (*c.calibrate_lidar_cmd)
    return bench::RunCalibrateLidarCommand(c.calibrate_lidar, command_line);
  if (*c.report_cmd) return bench::RunReportCommand(c.report);
  if (*c.crowd_check_cmd) return bench::RunCrowdCheckCommand(c.crowd_check);
  if (*c.render_cmd) {
    const auto files = bench::RenderResults(c.render_dir);
    std::cout << files.size() << " figures in " << c.render_dir.string() << "\n";
  }
  return 0;
}

// Runs the named subcommand; bad input is one line on stderr and exit code 2.
int RunReportingErrors(const Commands& c, const std::string& command_line) {
  try {
    return RunNamedCommand(c, command_line);
  } catch (const core::Error& e) {
    std::cerr << "retrace: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::filesystem::filesystem_error& e) {
    std::cerr << "retrace: error: " << e.what()
              << "\n";  // e.g. an output folder that cannot be written
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "retrace: internal error: " << e.what() << "\n";
    return kExitInternalError;
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"retrace: teaching-playback navigation without a consistent map, simulated"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "retrace " + retrace::bench::BuildVersion());
  Commands commands;
  AddCommands(app, commands);
  if (const std::optional<int> exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  return RunReportingErrors(commands, CommandLine(argc, argv));
}
