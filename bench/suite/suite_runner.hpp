#pragma once
// Runs a suite: for every entry and seed one teaching drive, then the entry's playback runs in
// each of its modes, then per mode the aggregate metrics — the same numbers `retrace run
// <scenario> --seed S --repeats R` gives. All of it goes through the episode scheduler
// (bench/engine/scheduler.hpp): the results do not depend on the number of threads.

#include <map>
#include <string>
#include <vector>

#include "bench/engine/progress.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/suite/suite_spec.hpp"
#include "io/config_override.hpp"

namespace retrace::bench {

/// The loaded scenario of each entry and seed, [entry][seed] in the suite's order.
struct SuiteScenarios {
  std::vector<std::vector<Scenario>> scenarios;
};

/// Loads every entry's scenario once per seed with the entry's `set`, then `extra` (the
/// command line's --set), then the seed and the repeats, and the entry's modes. Throws
/// core::Error naming the suite entry on any problem (an unknown `set` key, a route that is
/// not drivable, an override of `seed` or `playback.repeats`, which the suite decides);
/// nothing has run then. Loads on `jobs` threads (0: one per core).
SuiteScenarios LoadSuiteScenarios(const SuiteSpec& spec,
                                  const std::vector<io::ConfigOverride>& extra, int jobs = 0);

/// One suite metric: its value (mean over the seeds where it is defined; NaN when none) and
/// the value of each seed, in the entry's seed order.
struct SuiteMetric {
  double mean = 0.0;
  std::vector<double> per_seed;
};

struct SuiteResults {
  /// Every metric by "<entry>.<mode>.<FlatMetrics name>".
  std::map<std::string, SuiteMetric> metrics;
  int teaching_drives = 0;
  int playback_runs = 0;
};

/// Runs everything on `jobs` threads. Throws core::WorldError when a teaching drive cannot
/// finish its route.
SuiteResults RunSuite(const SuiteSpec& spec, const SuiteScenarios& scenarios, int jobs,
                      ProgressSink* progress = nullptr);

/// The mean of the finite values; NaN when there are none.
double MeanOfDefined(const std::vector<double>& values);

}  // namespace retrace::bench
