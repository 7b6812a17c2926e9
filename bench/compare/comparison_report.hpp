#pragma once
// The consistent-vs-partial study's numbers and files (`retrace compare`): per map mode and
// metric the per-seed values, their mean, standard deviation and 95 % confidence interval
// over seeds, and per non-reference mode the paired difference to the reference mode (seed by
// seed: same teaching drive, same playback seeds) with its interval and the ratio of means.
// comparison.json carries all of it, comparison.md is the table a paper prints, and
// ComparisonFigureData feeds viz::RenderComparisonFigure. Statistics: bench/metrics/statistics.hpp.

#include <array>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench/engine/trace.hpp"
#include "bench/metrics/statistics.hpp"
#include "viz/figure_data.hpp"

namespace retrace::bench {

/// The confidence of every interval in the study.
inline constexpr double kComparisonConfidence = 0.95;

/// One metric of the study, read from FlatMetrics (bench/metrics/flat_metrics.hpp) of a mode's
/// aggregate over the runs of one seed.
struct ComparedMetric {
  std::string key;              ///< name in comparison.json
  std::string source;           ///< FlatMetrics name of the value
  std::string divisor;          ///< FlatMetrics name the value is divided by; empty: none
  std::string label;            ///< row name in the table and the figure
  std::string unit;             ///< "m", "ms", "fraction", ...
  bool timing = false;          ///< measures the machine, not the navigation (IsTimingMetric)
  bool switching_only = false;  ///< defined for modes that switch maps only (n/a elsewhere)
};

/// The study's metrics in table order.
const std::vector<ComparedMetric>& ComparedMetrics();

/// The metric's value for `mode` from FlatMetrics output; NaN when missing, undefined (a zero
/// divisor) or not defined for the mode.
double ComparedValue(const ComparedMetric& metric, MapMode mode,
                     const std::map<std::string, double>& flat);

/// What was run and what came out: the input of Compare.
struct ComparisonInput {
  std::string scenario_name;
  std::string scenario_file;
  std::string command_line;
  std::string git_revision;
  double wall_time_s = 0.0;
  std::vector<std::uint64_t> seeds;  ///< scenario seed of each teaching drive
  int repeats = 0;                   ///< playback runs per mode and seed
  /// The compared columns' map modes (a mode repeats when several stacks are compared).
  std::vector<MapMode> modes;
  /// Per column its name: "mode", or "mode/stack" when several stacks are compared; empty: the
  /// modes' names.
  std::vector<std::string> labels;
  /// must be one of `modes`; the reference column is its first (with several stacks, the
  /// first stack's)
  MapMode reference = MapMode::kConsistent;

  /// Column m's name.
  std::string Label(std::size_t m) const;
  /// flat[m][s]: FlatMetrics of the aggregate of modes[m] on seeds[s].
  std::vector<std::vector<std::map<std::string, double>>> flat;
};

/// One metric across the modes.
struct MetricComparison {
  ComparedMetric metric;
  std::vector<std::vector<double>> per_seed;  ///< [mode][seed]; NaN where undefined
  std::vector<MeanInterval> summary;          ///< [mode], over seeds
  /// [mode]: the paired difference to the reference; none for the reference itself and where
  /// the metric is not defined for either mode.
  std::vector<std::optional<PairedComparison>> vs_reference;
};

struct Comparison {
  ComparisonInput input;
  std::size_t reference_index = 0;        ///< of input.reference in input.modes
  std::vector<MetricComparison> metrics;  ///< in ComparedMetrics() order
  /// [mode]: runs per outcome over all seeds (indexed by static_cast<int>(Outcome)).
  std::vector<std::array<int, 4>> outcomes;
};

/// The statistics of the study. Aborts when input.flat does not match modes × seeds or the
/// reference is not among the modes (the command checks both first).
Comparison Compare(ComparisonInput input);

/// comparison.json: scenario, command, git revision, seeds, repeats, confidence, the metrics'
/// descriptions, per mode the outcomes and per metric {per_seed, n, mean, sd, ci95: [lower,
/// upper], vs_reference: {n, mean, sd, ci95, significant, ratio_of_means}}; NaN is null.
nlohmann::json ComparisonJson(const Comparison& comparison);

/// comparison.md: the table (rows = metrics with units; columns = each mode's "mean [95 % CI]",
/// then per non-reference mode "mode − reference [95 % CI]" and "mode / reference"), with
/// what the numbers are and which differences are significant.
std::string ComparisonMarkdown(const Comparison& comparison);

/// The means with their intervals as error bars, one panel per metric.
viz::ComparisonFigureData ComparisonFigure(const Comparison& comparison);

}  // namespace retrace::bench
