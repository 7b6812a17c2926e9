#include "bench/cli/experiment_setup.hpp"

#include <iostream>

#include "bench/cli/progress.hpp"
#include "bench/engine/parallel.hpp"

namespace retrace::bench {

std::vector<io::ConfigOverride> CommandLineOverrides(const std::vector<std::string>& sets,
                                                     std::optional<std::uint64_t> seed,
                                                     std::optional<int> repeats) {
  std::vector<io::ConfigOverride> overrides;
  for (const std::string& text : sets) overrides.push_back(io::ParseOverride(text));
  if (seed) overrides.push_back(io::ParseOverride("seed=" + std::to_string(*seed)));
  if (repeats)
    overrides.push_back(io::ParseOverride("playback.repeats=" + std::to_string(*repeats)));
  return overrides;
}

void PrintScenarioWarnings(const Scenario& scenario) {
  for (const std::string& warning : scenario.warnings)
    std::cerr << "retrace: warning: " << warning << "\n";
}

ExperimentOptions CommandExperimentOptions(int repeats, int jobs, ProgressLine* progress) {
  ExperimentOptions options;
  options.repeats = repeats;
  options.jobs = jobs > 0 ? jobs : DefaultJobs();
  options.progress = progress;
  return options;
}

}  // namespace retrace::bench
