#pragma once
// Metrics by dotted name ("tracking_error_m.pooled.rms"): the vocabulary of suites, sweeps and
// comparisons.

#include <map>
#include <string>

#include "bench/metrics/metrics.hpp"

namespace retrace::bench {

/// Every number of ToJson(aggregate) by its dotted path, e.g. "success_rate",
/// "tracking_error_m.pooled.rms", "switch_error.max_m", "cpu.real_time_factor". null (NaN)
/// values are NaN; arrays are left out.
std::map<std::string, double> FlatMetrics(const AggregateMetrics& aggregate);

/// True for the metrics that measure the machine rather than the navigation (cpu.*): they are
/// reported, never compared against a baseline.
bool IsTimingMetric(const std::string& name);

}  // namespace retrace::bench
