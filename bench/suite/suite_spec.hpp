#pragma once
// Suite files (bench/suites/*.yaml): the scenarios, map modes and seeds of a regression
// benchmark, and for each metric how far it may move from the committed baseline.
//
//   name: ci                                  # letters, digits, _ and -; names the baseline
//   entries:
//     - scenario: ../../scenarios/small.yaml  # relative to the suite file
//       name: small                           # default: the scenario's name; unique
//       modes: [partial, single, consistent]
//       seeds: [1, 2, 3]                      # scenario seeds: one teaching drive each ...
//       repeats: 2                            # ... and playback runs per mode (default 2)
//       set: {nav.localizer.particles: 300}   # optional overrides, as `--set key.path=value`
//   metrics:                                  # pattern: tolerance (bench/suite/tolerance.hpp)
//     "*.partial.success_rate": {min: 1.0}                 # a bound
//     "*.*.tracking_error_m.pooled.rms": {abs: 0.02}       # fails if worse by > 0.02
//     "*.*.localization_error_m.pooled.rms": {rel: 0.25}   # ... by > 25 % of the baseline
//     "*.*.collisions.min_clearance_m": {abs: 0.05, min: 0.02, better: higher}
//     "*.*.cpu.real_time_factor": {report: true}           # shown, never gated
//
// A suite metric is "<entry>.<mode>.<FlatMetrics name>" (bench/suite/metric_pattern.hpp for the
// patterns); its value is the mean, over the entry's seeds, of that seed's aggregate metric
// over its playback runs (seeds where it is undefined, NaN, are left out; NaN when it is
// undefined for every seed). When several patterns match a metric the last one decides, so
// general rules come first and exceptions after. Only metrics some pattern matches appear in
// the report; every metric goes into the baseline. A tolerance has any of abs, rel (>= 0),
// min, max (a bound; min <= max) and better (higher|lower), or report: true alone.
//
// Strict: unknown keys, a missing scenario file, duplicate entry names or seeds, a pattern
// that matches no metric or that a later pattern overrides everywhere are ConfigErrors naming
// the file and line. A `set` key the scenario does not have is caught when the scenarios are
// loaded (bench/suite/suite_runner.hpp).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/engine/trace.hpp"
#include "bench/suite/tolerance.hpp"
#include "io/config_override.hpp"

namespace retrace::bench {

struct SuiteEntry {
  std::string name;
  std::string scenario_text;       ///< the scenario path as written in the suite
  std::filesystem::path scenario;  ///< resolved against the suite file's folder
  std::vector<MapMode> modes;
  std::vector<std::uint64_t> seeds;
  int repeats = 2;
  std::vector<io::ConfigOverride> overrides;  ///< `set`, in file order
  int line = 0;                               ///< of the entry in the suite file (1-based)
};

struct MetricRule {
  std::string pattern;
  Tolerance tolerance;
  int line = 0;
};

struct SuiteSpec {
  std::string name;
  std::filesystem::path source;
  std::string digest;  ///< "fnv1a64:<16 hex digits>" of the file's bytes
  std::vector<SuiteEntry> entries;
  std::vector<MetricRule> rules;
};

/// Reads and checks a suite file (see above). Throws core::IoError when it cannot be read,
/// core::ConfigError ("<file>:<line>: <key>: <problem>") when it is malformed.
SuiteSpec LoadSuiteSpec(const std::filesystem::path& file);

/// Every metric name of the suite, "<entry>.<mode>.<metric>", by entry, mode (in the suite's
/// order) and FlatMetrics name.
std::vector<std::string> SuiteMetricNames(const SuiteSpec& spec);

/// A suite metric name in its parts. Entry and mode names hold no dots, so the first two dots
/// split it: "office.partial.tracking_error_m.pooled.rms" is office, partial and
/// tracking_error_m.pooled.rms. A name with fewer than two dots is all metric.
struct SuiteMetricName {
  std::string entry;
  std::string mode;
  std::string metric;  ///< the FlatMetrics name
};
SuiteMetricName SplitSuiteMetricName(const std::string& name);

/// The part of a suite that `retrace bench --only` runs. Each selector is "<entry>" (all its
/// modes) or "<entry>.<mode>"; the entries and modes keep the suite's order. Throws
/// core::ConfigError when a selector names no entry of the suite or a mode its entry does not
/// run (the message lists what there is).
SuiteSpec SelectRuns(const SuiteSpec& spec, const std::vector<std::string>& selectors);

/// The FlatMetrics names (bench/metrics/flat_metrics.hpp) every mode of an entry has.
const std::vector<std::string>& AggregateMetricNames();

}  // namespace retrace::bench
