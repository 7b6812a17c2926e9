#pragma once
// What the commands that run experiments (`retrace run`, `teach`, `playback` and `compare`) set
// up alike: the scenario's overrides from the command line, its warnings on stderr, and the
// options of the experiments' runs.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bench/engine/scenario.hpp"
#include "bench/metrics/experiment.hpp"
#include "io/config_override.hpp"

namespace retrace::bench {

class ProgressLine;

/// The overrides a command line gives a scenario, in this order: every `--set` (a.b.c=value),
/// then `seed` and `playback.repeats` where given. Throws core::ConfigError for a malformed
/// `--set`.
std::vector<io::ConfigOverride> CommandLineOverrides(const std::vector<std::string>& sets,
                                                     std::optional<std::uint64_t> seed,
                                                     std::optional<int> repeats);

/// Prints the scenario's warnings on stderr, one line each.
void PrintScenarioWarnings(const Scenario& scenario);

/// Options for `repeats` playback runs per mode on `jobs` threads (0: one per core), showing
/// progress on `progress`.
ExperimentOptions CommandExperimentOptions(int repeats, int jobs, ProgressLine* progress);

}  // namespace retrace::bench
