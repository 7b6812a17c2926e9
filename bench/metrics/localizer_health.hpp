#pragma once
// How the localizer held, by its own account and by what its estimate did (docs/DESIGN.md §6,
// "Metrics"): the time it deemed itself lost, how often it became lost, the recovery trials that
// replaced its belief, and the largest single-step move of its estimate beyond what the odometry
// explains — a one-tick jump that an RMS hides. The same for a simulated run and a log's replay.

#include <limits>
#include <span>

#include "bench/engine/trace.hpp"
#include "core/pose2.hpp"

namespace retrace::bench {

/// One sample of the estimate's track.
struct EstimateSample {
  double time = 0.0;  ///< s
  int map = 0;        ///< the map the estimate is in
  core::Pose2 X_MR;   ///< the estimate in that map
  core::Pose2 X_OR;   ///< the wheel odometry at the same instant
  bool lost = false;  ///< the localizer's own verdict
};

struct LocalizerHealth {
  double lost_time_s = 0.0;  ///< each lost sample holds until the next
  int lost_spells = 0;       ///< times the localizer went from not lost to lost
  int reacquisitions = 0;    ///< recovery trials that replaced the belief
  /// Max over consecutive samples in the same map of |X_MR(k) − X_MR(k−1) ⊕ odometry step| (m):
  /// how far the estimate moved beyond the odometry's motion between them. NaN: < 2 samples.
  double max_jump_m = std::numeric_limits<double>::quiet_NaN();
  double max_jump_time_s = std::numeric_limits<double>::quiet_NaN();  ///< when it happened
};

LocalizerHealth ComputeLocalizerHealth(std::span<const EstimateSample> track,
                                       std::span<const LocalizerSample> updates);

/// Over several runs: sums of the times and counts, the largest jump (and its time, of the
/// run that had it).
LocalizerHealth CombineLocalizerHealth(std::span<const LocalizerHealth> runs);

}  // namespace retrace::bench
