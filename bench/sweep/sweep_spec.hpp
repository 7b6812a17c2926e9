#pragma once
// Sweep files (bench/sweeps/*.yaml): one base scenario, the scenario keys to vary, how many
// replications of each combination, and which metrics to collect. Expanded here into the
// combinations of parameter values; bench/sweep/sweep_plan.* checks each against the scenario
// and bench/cli/sweep_command.* runs them.
//
//   name: particles                         # default: the file's stem
//   scenario: ../../scenarios/office.yaml   # relative to the sweep file
//   mode: partial                        # map mode of every case (default partial), unless
//                                        #   `mode` is itself a varied parameter
//   set: {playback.start_offset_xy: 0.2, limits: {stall_time: 30}}   # fixed for every case;
//                                        #   nested maps are flattened into dotted keys, lists
//                                        #   and scalars replace the value whole
//   repeats: 3                           # replications per combination; repeat r runs with
//                                        #   seed = the scenario's seed + r (default 1)
//   grid:                                # every combination of these lists (first key slowest)
//     nav.localizer.particles: [100, 300, 1000]
//     nav.localizer.rejection.enabled: [true, false]
//   zip:                                 # lists of equal length, varied together (row i of all)
//     sim.odometry.alpha1: [1e-4, 2e-4, 4e-4]
//     sim.odometry.alpha3: [5e-4, 1e-3, 2e-3]
//   random:                              # `samples` draws, deterministic given `seed`
//     samples: 16
//     seed: 7
//     parameters:
//       nav.localizer.rejection.chi: {uniform: [0.7, 0.99]}        # [lo, hi)
//       nav.localizer.augmented.alpha_fast: {log_uniform: [0.01, 0.3]}   # 0 < lo < hi
//       nav.localizer.particles: {int_uniform: [100, 2000]}        # integers, both ends included
//       mode: {choice: [partial, consistent]}                      # one of the values
//   labels: [drift]                      # varied keys that only name a combination: recorded
//                                        #   in results.csv and plotted, not applied to the
//                                        #   scenario (`drift: [0.5, 1, 2]` zipped with the keys
//                                        #   it scales)
//   plot: [drift, mode]                  # the parameters sweep.png plots against (default: all)
//   metrics: [success_rate, tracking_error_m.pooled.rms]   # FlatMetrics names (default:
//                                        #   DefaultSweepMetrics)
//
// Combinations = (grid product) x (zip rows) x (random samples) of the sections present, in
// that nesting order (grid outermost); with none of them there is one combination. A case is
// (combination c, repeat r) with id c * repeats + r. Every key of the sections is a scenario
// key path as for `--set` (list elements by index: `events.0.pedestrians.count`), or `mode`. A
// key may be varied in one section only, and not also fixed by `set` or `--set`. `seed` may be
// varied; `playback.repeats` and `modes` may not (each case is one playback run of one mode).
// Values may be any YAML (a list for a vector key); a parameter's value is written into
// results.csv as its YAML text (flow style for lists and maps).
//
// Metrics whose name starts with `cpu.` measure the machine, not the navigation: they go to
// timings.csv, never results.csv, so that results are identical on every machine.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/engine/trace.hpp"
#include "io/config_override.hpp"

namespace retrace::bench {

/// Where a key of the sweep file came from, for error messages.
struct SweepKeySource {
  std::string section;  ///< "set", "grid", "zip", "random", or "--set"
  int line = 0;         ///< 1-based line in the sweep file; 0 for --set
};

/// A sweep file, expanded.
struct SweepSpec {
  std::filesystem::path file;  ///< the sweep file as given
  std::string name;
  std::filesystem::path scenario;  ///< resolved against the sweep file's folder
  MapMode mode = MapMode::kPartial;
  /// `set` (flattened), then the command line's --set: applied to every case, before the
  /// varied parameters.
  std::vector<io::ConfigOverride> fixed;
  std::vector<SweepKeySource> fixed_sources;  ///< parallel to `fixed`
  int repeats = 1;
  /// The varied keys in column order: grid keys, zip keys, random keys, each in file order.
  std::vector<std::string> parameters;
  std::vector<SweepKeySource> parameter_sources;  ///< parallel to `parameters`
  /// The parameters that are labels (recorded, not applied), and those sweep.png plots.
  std::vector<std::string> labels;
  std::vector<std::string> plot_parameters;
  /// combinations[c][p]: the value of parameters[p] in combination c, as YAML text.
  std::vector<std::vector<std::string>> combinations;
  /// The collected metrics in file order: `metrics` are the navigation ones (results.csv),
  /// `timing_metrics` the cpu.* ones (timings.csv).
  std::vector<std::string> metrics;
  std::vector<std::string> timing_metrics;

  std::size_t case_count() const { return combinations.size() * static_cast<std::size_t>(repeats); }
  /// The map mode of combination c: the varied `mode`, or `mode`.
  MapMode CombinationMode(std::size_t c) const;
  /// The scenario overrides of combination c: `fixed`, then the varied keys but `mode` and the
  /// labels.
  std::vector<io::ConfigOverride> CombinationOverrides(std::size_t c) const;
  /// "key=value, key=value" of combination c, for messages.
  std::string DescribeCombination(std::size_t c) const;
};

/// The metrics collected when a sweep file lists none.
std::vector<std::string> DefaultSweepMetrics();

/// Every metric name a sweep may collect: the keys of FlatMetrics.
const std::vector<std::string>& KnownSweepMetrics();

/// Loads and expands a sweep file; `cli_overrides` (the command line's --set) join `set`.
/// Checks the file's own structure only (bench/sweep/sweep_plan.hpp checks every combination
/// against the scenario). Throws core::ConfigError naming the sweep file, line and key: unknown
/// keys, an empty grid or zip list, zip lists of different lengths, a bad distribution, a key
/// varied twice or both varied and fixed, a label or plotted parameter that is not varied, an
/// unknown metric, too many cases; core::IoError if
/// the file cannot be read.
SweepSpec LoadSweepSpec(const std::filesystem::path& file,
                        const std::vector<io::ConfigOverride>& cli_overrides = {});

}  // namespace retrace::bench
