#pragma once
// The short text printed at the end of `retrace run`: per mode, the success rate and the
// headline metrics, and where the results are.

#include <filesystem>
#include <string>
#include <vector>

#include "bench/engine/scenario.hpp"
#include "bench/metrics/metrics.hpp"

namespace retrace::bench {

struct ModeSummary {
  MapMode mode = MapMode::kPartial;
  int runs = 0;
  int successes = 0;
  AggregateMetrics aggregate;
};

ModeSummary SummarizeMode(MapMode mode, const AggregateMetrics& aggregate);

/// The teaching drive's speed, for the summary: simulated and CPU seconds (cpu 0: no drive ran).
struct TeachSpeed {
  double duration_s = 0.0;
  double cpu_time_s = 0.0;
};

/// The summary `retrace run` prints: the scenario and its maps, one table row per mode, how the
/// switching modes' maps were cut, the teaching drive's speed and where the results are.
std::string SummaryText(const Scenario& scenario, const std::vector<ModeSummary>& modes,
                        const TeachSpeed& teach, const std::filesystem::path& out,
                        double wall_time_s);

}  // namespace retrace::bench
