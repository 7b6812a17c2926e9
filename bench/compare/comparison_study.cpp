#include "bench/compare/comparison_study.hpp"

#include <algorithm>
#include <chrono>

#include "bench/engine/mode_list.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/stack_registry.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/metrics/experiment.hpp"
#include "bench/metrics/flat_metrics.hpp"
#include "bench/metrics/provenance.hpp"
#include "bench/output/staged_folder.hpp"
#include "core/check.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/json_writer.hpp"
#include "viz/figures.hpp"

namespace retrace::bench {
namespace {

// The modes compared; with one stack at least two (several stacks may compare one mode).
std::vector<MapMode> ParseModes(const std::vector<std::string>& names, std::size_t stacks) {
  std::vector<MapMode> modes = ParseModeList(names, "--modes");
  if (modes.size() * std::max<std::size_t>(stacks, 1) < 2) {
    throw core::ConfigError("--modes", "a comparison needs at least two modes (or two --stacks)");
  }
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

// The stacks compared: those asked for (each registered, its options valid, none twice), else the
// scenario's own.
std::vector<std::string> StudyStacks(const Scenario& scenario, const ComparisonRequest& request) {
  if (request.stacks.empty()) return {scenario.config.playback.stack};
  for (std::size_t i = 0; i < request.stacks.size(); ++i) {
    const std::string& name = request.stacks[i];
    try {
      ValidateStackChoice(name, scenario.config.playback.stack_options);
    } catch (const core::ConfigError& e) {
      throw core::ConfigError("--stacks", e.detail());
    }
    if (std::find(request.stacks.begin(), request.stacks.begin() + static_cast<long>(i), name) !=
        request.stacks.begin() + static_cast<long>(i)) {
      throw core::ConfigError("--stacks", "'" + name + "' is named twice");
    }
  }
  return request.stacks;
}

// The study before its runs: what it compares (each stack in each mode), over which seeds, and
// room for each column's and seed's metrics.
ComparisonInput StudyInput(const Scenario& scenario, const ComparisonRequest& request,
                           const std::vector<MapMode>& modes, MapMode reference,
                           const std::vector<std::string>& stacks,
                           const std::string& command_line) {
  ComparisonInput input;
  input.scenario_name = scenario.config.name;
  input.scenario_file = request.scenario.string();
  input.command_line = command_line;
  input.git_revision = BuildRevision();
  input.repeats = scenario.config.playback.repeats;
  for (const std::string& stack : stacks) {
    for (const MapMode mode : modes) {
      input.modes.push_back(mode);
      if (stacks.size() > 1) {
        input.labels.push_back(std::string(core::EnumName(mode)) + "/" + stack);
      }
    }
  }
  input.reference = reference;
  const std::size_t n_seeds = static_cast<std::size_t>(request.seeds);
  for (std::size_t i = 0; i < n_seeds; ++i) input.seeds.push_back(scenario.config.seed + i);
  input.flat.assign(input.modes.size(), std::vector<std::map<std::string, double>>(n_seeds));
  return input;
}

// Every seed's teaching drive, then every playback run, through the one scheduler (the numbers
// do not depend on --jobs), once per stack (its columns follow the modes); each column's and
// seed's metrics into `input`.
void RunSeedExperiments(const Scenario& scenario, const std::vector<MapMode>& modes,
                        const std::vector<std::string>& stacks,
                        const ExperimentOptions& run_options, ComparisonInput* input) {
  const std::size_t n_seeds = input->seeds.size();
  for (std::size_t k = 0; k < stacks.size(); ++k) {
    std::vector<Scenario> seeded(n_seeds, scenario);
    std::vector<const Scenario*> studies;
    for (std::size_t s = 0; s < n_seeds; ++s) {
      seeded[s].config.seed = input->seeds[s];
      seeded[s].config.playback.stack = stacks[k];
      studies.push_back(&seeded[s]);
    }
    const std::vector<Experiment> experiments = RunExperiments(studies, modes, run_options);
    for (std::size_t s = 0; s < n_seeds; ++s) {
      for (std::size_t m = 0; m < modes.size(); ++m) {
        RETRACE_CHECK(experiments[s].modes[m].teach.mode == modes[m]);
        input->flat[k * modes.size() + m][s] = FlatMetrics(experiments[s].modes[m].aggregate);
      }
    }
  }
}

// comparison.json, comparison.md and comparison.png into `folder`.
void WriteComparisonFiles(const ComparisonStudy& study, const std::filesystem::path& folder) {
  io::WriteJsonAtomic(folder / "comparison.json", ComparisonJson(study.comparison));
  io::WriteFileAtomic(folder / "comparison.md", study.markdown);
  viz::RenderComparisonFigure(ComparisonFigure(study.comparison), folder / "comparison.png");
}

}  // namespace

ComparisonStudy RunComparisonStudy(const ComparisonRequest& request,
                                   const std::string& command_line, ProgressSink* progress) {
  const auto wall_start = std::chrono::steady_clock::now();
  // Every check before any work: nothing is run or written for bad input.
  const std::vector<MapMode> modes = ParseModes(request.modes, request.stacks.size());
  const MapMode reference = ParseReference(request.reference, modes);
  RequireSeedsForInterval(request.seeds);
  const Scenario scenario = LoadScenario(
      request.scenario, CommandLineOverrides(request.overrides, std::nullopt, request.repeats));
  RequireSwitchingModeIfOnline(scenario, modes);
  for (const std::string& warning : scenario.warnings) Warn(progress, warning);
  const std::vector<std::string> stacks = StudyStacks(scenario, request);
  ComparisonStudy study;
  study.out = request.out.empty()
                  ? std::filesystem::path("results") / "compare" / scenario.config.name
                  : request.out;
  ComparisonInput input = StudyInput(scenario, request, modes, reference, stacks, command_line);

  // Staged before the runs so that an unwritable --out fails now, not after them.
  StagedFolder folder(study.out);
  RunSeedExperiments(scenario, modes, stacks,
                     RunOptionsFor(input.repeats, request.jobs, progress), &input);
  input.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  study.comparison = Compare(std::move(input));
  study.markdown = ComparisonMarkdown(study.comparison);
  WriteComparisonFiles(study, folder.path());
  folder.Commit();
  return study;
}

std::string ComparisonStudySummary(const ComparisonStudy& study) {
  return study.markdown + "\nWritten: " + (study.out / "comparison.json").string() +
         ", comparison.md, comparison.png";
}

}  // namespace retrace::bench
