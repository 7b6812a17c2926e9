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

std::string SummaryText(const Scenario& scenario, const std::vector<ModeSummary>& modes,
                        const std::filesystem::path& out, double wall_time_s);

}  // namespace retrace::bench
