#pragma once
// Contact incidents of a run (docs/DESIGN.md §6, "collisions").

#include "bench/engine/metrics_config.hpp"
#include "bench/engine/trace.hpp"
#include "bench/metrics/metrics.hpp"

namespace retrace::bench::internal {

/// The collision statistics of one run.
CollisionStats Collisions(const RunTrace& run, const MetricsConfig& config);

}  // namespace retrace::bench::internal
