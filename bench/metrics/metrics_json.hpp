#pragma once
// The metrics as JSON (metrics.json, comparison.json, flat metric names): nlohmann-json stays
// out of bench/metrics/metrics.hpp so that what only computes metrics does not parse it.

#include <nlohmann/json.hpp>

#include "bench/metrics/metrics.hpp"

namespace retrace::bench {

/// JSON objects with snake_case keys carrying units; NaN and infinities become null. The
/// repeatability stations are one compact array of rows [s_m, offset of each run...] (m,
/// rounded to 0.1 mm).
nlohmann::json ToJson(const Summary& summary);
nlohmann::json ToJson(const LocalizerHealth& health);
nlohmann::json ToJson(const RunMetrics& metrics);
nlohmann::json ToJson(const AggregateMetrics& metrics);

}  // namespace retrace::bench
