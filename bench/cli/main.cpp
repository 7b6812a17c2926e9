// The `retrace` command-line program. Exit codes: 0 success; 1 the runs completed but
// navigation failed where the scenario requires success; 2 bad input (one clear line on
// stderr, nothing written); 3 an internal error.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include "bench/cli/bench_command.hpp"
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
#include "core/errors.hpp"

namespace {

constexpr int kExitBadInput = 2;
constexpr int kExitInternalError = 3;  // a bug in retrace, never bad input

std::string CommandLine(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) line += (i ? " " : "") + std::string(argv[i]);
  return line;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace retrace;
  CLI::App app{"retrace: teaching-playback navigation without a consistent map, simulated"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "retrace 0.1.0");

  bench::RunOptions run;
  CLI::App* run_cmd = app.add_subcommand(
      "run",
      "Teach the scenario's route, play it back in each map mode, write metrics and trajectories");
  bench::AddRunOptions(run_cmd, &run, bench::RunPhases::kAll);

  bench::RunOptions teach;
  CLI::App* teach_cmd =
      app.add_subcommand("teach", "Drive the route once and write the teach bundles only");
  bench::AddRunOptions(teach_cmd, &teach, bench::RunPhases::kTeachOnly);

  bench::RunOptions playback;
  CLI::App* playback_cmd =
      app.add_subcommand("playback", "Play back a teach folder written by an earlier run or teach");
  bench::AddRunOptions(playback_cmd, &playback, bench::RunPhases::kPlaybackOnly);

  bench::WorldCommandOptions world;
  CLI::App* world_cmd =
      app.add_subcommand("world", "Load and check a world file, render it to a PNG");
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

  std::filesystem::path render_dir;
  CLI::App* render_cmd = app.add_subcommand(
      "render", "Render the figures of a results folder again, without rerunning");
  render_cmd
      ->add_option("results", render_dir, "Results folder of `retrace run` (results/<scenario>)")
      ->required();

  bench::ReportOptions report;
  CLI::App* report_cmd = app.add_subcommand(
      "report",
      "Write <dir>/report.html: one self-contained page of a results folder's tables, figures, "
      "comparison, regressions and manifests");
  bench::AddReportOptions(report_cmd, &report);

  bench::GenerateCampusOptions campus;
  CLI::App* campus_cmd = app.add_subcommand(
      "generate-campus",
      "Turn a route into a campus world: buildings, hedges, trees, poles, benches, pedestrians");
  bench::AddGenerateCampusOptions(campus_cmd, &campus);

  bench::GenerateTourOptions tour;
  CLI::App* tour_cmd = app.add_subcommand(
      "generate-tour",
      "Write a random looped tour, a campus world round it and a scenario that drives it");
  bench::AddGenerateTourOptions(tour_cmd, &tour);

  bench::CompareOptions compare;
  CLI::App* compare_cmd = app.add_subcommand(
      "compare",
      "Compare map modes over several seeds: paired differences with 95% confidence intervals");
  bench::AddCompareOptions(compare_cmd, &compare);

  bench::BenchOptions bench_options;
  CLI::App* bench_cmd = app.add_subcommand("bench",
                                           "Run a regression suite and compare its metrics with "
                                           "the committed baseline (exit 1 on a regression)");
  bench::AddBenchOptions(bench_cmd, &bench_options);

  bench::SweepOptions sweep;
  CLI::App* sweep_cmd = app.add_subcommand(
      "sweep",
      "Run a parameter sweep: every case of a sweep file, in parallel, resumable, in shards");
  bench::AddSweepOptions(sweep_cmd, &sweep);

  bench::MergeOptions merge;
  CLI::App* merge_cmd =
      app.add_subcommand("merge", "Join the results folders of a sweep's shards into one");
  bench::AddMergeOptions(merge_cmd, &merge);

  bench::LogInfoOptions log_info;
  CLI::App* log_info_cmd = app.add_subcommand(
      "log-info",
      "Describe a recorded log (CARMEN, MCAP, rosbag2): topics, scans, odometry, reference");
  bench::AddLogInfoOptions(log_info_cmd, &log_info);

  bench::LogTeachOptions log_teach;
  CLI::App* log_teach_cmd = app.add_subcommand(
      "log-teach", "Build the teach folders (partial maps, paths) of a recorded log's drive");
  bench::AddLogTeachOptions(log_teach_cmd, &log_teach);

  bench::LogLocalizeOptions log_localize;
  CLI::App* log_localize_cmd = app.add_subcommand(
      "log-localize",
      "Localize a recorded log in a teach folder's partial maps, measured against its reference");
  bench::AddLogLocalizeOptions(log_localize_cmd, &log_localize);

  bench::LogSimulateOptions log_simulate;
  CLI::App* log_simulate_cmd = app.add_subcommand(
      "log-simulate",
      "Drive a log's reference again in the simulator, in its consistent map, with its LiDAR: "
      "the same log with simulated scans");
  bench::AddLogSimulateOptions(log_simulate_cmd, &log_simulate);

  bench::LogCompareOptions log_compare;
  CLI::App* log_compare_cmd = app.add_subcommand(
      "log-compare", "Put log-localize results side by side: one table, one figure of errors");
  bench::AddLogCompareOptions(log_compare_cmd, &log_compare);

  bench::CrowdCheckOptions crowd_check;
  CLI::App* crowd_check_cmd = app.add_subcommand(
      "crowd-check",
      "Check the pedestrian crowd against Weidmann's speed-density curve (fundamental diagram)");
  bench::AddCrowdCheckOptions(crowd_check_cmd, &crowd_check);

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

  const std::string command_line = CommandLine(argc, argv);
  try {
    if (*run_cmd) return bench::RunRunCommand(run, bench::RunPhases::kAll, command_line);
    if (*teach_cmd) return bench::RunRunCommand(teach, bench::RunPhases::kTeachOnly, command_line);
    if (*playback_cmd)
      return bench::RunRunCommand(playback, bench::RunPhases::kPlaybackOnly, command_line);
    if (*world_cmd) std::cout << bench::RunWorldCommand(world) << "\n";
    if (*campus_cmd) std::cout << bench::RunGenerateCampusCommand(campus) << "\n";
    if (*tour_cmd) std::cout << bench::RunGenerateTourCommand(tour) << "\n";
    if (*compare_cmd) return bench::RunCompareCommand(compare, command_line);
    if (*bench_cmd) return bench::RunBenchCommand(bench_options);
    if (*sweep_cmd) return bench::RunSweepCommand(sweep, command_line);
    if (*merge_cmd) return bench::RunMergeCommand(merge, command_line);
    if (*log_info_cmd) return bench::RunLogInfoCommand(log_info);
    if (*log_teach_cmd) return bench::RunLogTeachCommand(log_teach, command_line);
    if (*log_localize_cmd) return bench::RunLogLocalizeCommand(log_localize, command_line);
    if (*log_simulate_cmd) return bench::RunLogSimulateCommand(log_simulate);
    if (*log_compare_cmd) return bench::RunLogCompareCommand(log_compare);
    if (*report_cmd) return bench::RunReportCommand(report);
    if (*crowd_check_cmd) return bench::RunCrowdCheckCommand(crowd_check);
    if (*render_cmd) {
      const auto files = bench::RenderResults(render_dir);
      std::cout << files.size() << " figures in " << render_dir.string() << "\n";
    }
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
  return 0;
}
