#include "bench/cli/compare_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <iostream>
#include <optional>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/experiment_setup.hpp"
#include "bench/cli/mode_list.hpp"
#include "bench/cli/progress.hpp"
#include "bench/cli/report_command.hpp"
#include "bench/cli/shared_options.hpp"
#include "bench/compare/comparison_report.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/metrics/experiment.hpp"
#include "bench/metrics/flat_metrics.hpp"
#include "bench/output/staged_folder.hpp"
#include "core/check.hpp"
#include "core/errors.hpp"
#include "git_revision.hpp"
#include "io/atomic_file.hpp"
#include "io/json_writer.hpp"
#include "viz/figures.hpp"

namespace retrace::bench {
namespace {

std::vector<MapMode> ParseModes(const std::vector<std::string>& names) {
  std::vector<MapMode> modes = ParseModeList(names, "--modes");
  if (modes.size() < 2) throw core::ConfigError("--modes", "a comparison needs at least two modes");
  return modes;
}

MapMode ParseReference(const std::string& name, const std::vector<MapMode>& modes) {
  const auto mode = core::ParseEnum<MapMode>(name);
  if (!mode) {
    throw core::ConfigError("--reference", "unknown mode '" + name + "'; expected one of: " +
                                               core::EnumNameList<MapMode>());
  }
  if (std::find(modes.begin(), modes.end(), *mode) == modes.end()) {
    throw core::ConfigError("--reference",
                            "mode '" + name + "' is not among the compared modes (--modes)");
  }
  return *mode;
}

// A confidence interval needs two seeds at least.
void RequireSeedsForInterval(int seeds) {
  if (seeds < 2) {
    throw core::ConfigError(
        "--seeds",
        "at least 2 seeds are needed for a confidence interval, got " + std::to_string(seeds));
  }
}

// The study before its runs: what it compares, over which seeds, and room for each mode's and
// seed's metrics.
ComparisonInput StudyInput(const Scenario& scenario, const CompareOptions& options,
                           const std::vector<MapMode>& modes, MapMode reference,
                           const std::string& command_line) {
  ComparisonInput input;
  input.scenario_name = scenario.config.name;
  input.scenario_file = options.scenario.string();
  input.command_line = command_line;
  input.git_revision = RETRACE_GIT_REVISION;
  input.repeats = scenario.config.playback.repeats;
  input.modes = modes;
  input.reference = reference;
  const std::size_t n_seeds = static_cast<std::size_t>(options.seeds);
  for (std::size_t i = 0; i < n_seeds; ++i) input.seeds.push_back(scenario.config.seed + i);
  input.flat.assign(modes.size(), std::vector<std::map<std::string, double>>(n_seeds));
  return input;
}

// Every seed's teaching drive, then every playback run, through the one scheduler (the numbers
// do not depend on --jobs); each mode's and seed's metrics into `input`.
void RunSeedExperiments(const Scenario& scenario, const ExperimentOptions& run_options,
                        ComparisonInput* input) {
  const std::size_t n_seeds = input->seeds.size();
  const std::vector<MapMode>& modes = input->modes;
  std::vector<Scenario> seeded(n_seeds, scenario);
  std::vector<const Scenario*> studies;
  for (std::size_t s = 0; s < n_seeds; ++s) {
    seeded[s].config.seed = input->seeds[s];
    studies.push_back(&seeded[s]);
  }
  const std::vector<Experiment> experiments = RunExperiments(studies, modes, run_options);
  for (std::size_t s = 0; s < n_seeds; ++s) {
    for (std::size_t m = 0; m < modes.size(); ++m) {
      RETRACE_CHECK(experiments[s].modes[m].teach.mode == modes[m]);
      input->flat[m][s] = FlatMetrics(experiments[s].modes[m].aggregate);
    }
  }
}

// comparison.json, comparison.md and comparison.png into `folder`; the markdown.
std::string WriteComparisonFiles(const Comparison& comparison,
                                 const std::filesystem::path& folder) {
  const std::string markdown = ComparisonMarkdown(comparison);
  io::WriteJsonAtomic(folder / "comparison.json", ComparisonJson(comparison));
  io::WriteFileAtomic(folder / "comparison.md", markdown);
  viz::RenderComparisonFigure(ComparisonFigure(comparison), folder / "comparison.png");
  return markdown;
}

}  // namespace

void AddCompareOptions(CLI::App* command, CompareOptions* options) {
  command->add_option("scenario", options->scenario, "Scenario file (YAML)")->required();
  command->add_option("--modes", options->modes, "Map modes to compare, comma-separated, or all")
      ->delimiter(',')
      ->default_str("all");
  command->add_option("--reference", options->reference, "The mode the others are compared against")
      ->default_str("consistent");
  command->add_option("--seeds", options->seeds, "Scenario seeds (seed, seed + 1, ...), at least 2")
      ->default_str("5");
  command
      ->add_option("--repeats", options->repeats,
                   "Playback runs per mode and seed (default: the scenario's)")
      ->check(kPositive);
  AddJobsOption(command, &options->jobs);
  AddOutOption(command, &options->out, "Output folder (default: results/compare/<scenario name>)");
  AddSetOption(command, &options->overrides, "a scenario key: a.b.c=value");
  AddNoReportFlag(command, &options->report,
                  "Do not write report.html, the study's page of tables and figures (retrace "
                  "report does it later)");
}

int RunCompareCommand(const CompareOptions& options, const std::string& command_line) {
  const auto wall_start = std::chrono::steady_clock::now();
  // Every check before any work: nothing is run or written for bad input.
  const std::vector<MapMode> modes = ParseModes(options.modes);
  const MapMode reference = ParseReference(options.reference, modes);
  RequireSeedsForInterval(options.seeds);
  const Scenario scenario = LoadScenario(
      options.scenario, CommandLineOverrides(options.overrides, std::nullopt, options.repeats));
  RequireSwitchingModeIfOnline(scenario, modes);
  PrintScenarioWarnings(scenario);
  const std::filesystem::path out =
      options.out.empty() ? std::filesystem::path("results") / "compare" / scenario.config.name
                          : options.out;
  ComparisonInput input = StudyInput(scenario, options, modes, reference, command_line);

  // Staged before the runs so that an unwritable --out fails now, not after them.
  StagedFolder folder(out);
  ProgressLine progress;
  RunSeedExperiments(scenario, CommandExperimentOptions(input.repeats, options.jobs, &progress),
                     &input);
  progress.Clear();
  input.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  const std::string markdown = WriteComparisonFiles(Compare(std::move(input)), folder.path());
  folder.Commit();
  std::cout << markdown << "\nWritten: " << (out / "comparison.json").string()
            << ", comparison.md, comparison.png\n";
  if (options.report) WriteReportAtEnd(out);
  return 0;
}

}  // namespace retrace::bench
