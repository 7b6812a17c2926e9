#pragma once
// The social navigation metrics of one run and over runs (definitions in metrics.hpp).

#include <vector>

#include "bench/metrics/metrics.hpp"

namespace retrace::bench::internal {

/// Time (s) until two discs whose centres are Δp apart (m) and close at relative velocity Δv
/// (m/s; their distance at time t is |Δp + Δv t|) touch, the sum of their radii being `reach`
/// (m): 0 when they overlap now, +inf when they never touch.
double TimeToCollision(const core::Vec2& dp, const core::Vec2& dv, double reach);

/// The social metrics of `run`; taught_length_m and taught_time_s describe the teaching drive,
/// success / path_length_m / time_s the run (RunMetrics).
SocialStats Social(const RunTrace& run, double taught_length_m, double taught_time_s, bool success,
                   double path_length_m, double time_s, const MetricsConfig& config);

/// The social metrics over runs (AggregateMetrics::social).
SocialStats AggregateSocial(const std::vector<RunMetrics>& runs);

/// Per behaviour toward the robot: the people met, their closest gap and zone times
/// (out->by_behaviour, their crowd reactions left as they are), and for a failed run
/// out->stopped_by. dt: the samples' durations (s).
void BehaviourBreakdown(const RunTrace& run, const std::vector<double>& dt, bool success,
                        const MetricsConfig& config, SocialStats* out);

/// Adds one run's by_behaviour and stopped_by to the aggregate `a` of `runs` runs.
void AddBehaviours(const SocialStats& run, double runs, SocialStats* a);

}  // namespace retrace::bench::internal
