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
  /// m: how much farther the estimate is from the truth than the sample before it was, both
  /// measured against this sample's local truth (ErrorIncrease); NaN without a truth, at the
  /// first sample and across a map switch.
  double error_increase = std::numeric_limits<double>::quiet_NaN();
  bool off_map = false;  ///< no map covered the place: the stack ran on odometry alone
  /// m: the localization error against the truth; NaN without one.
  double error = std::numeric_limits<double>::quiet_NaN();
};

/// m: an error above this while the stack says it is localized is a silent failure ...
inline constexpr double kSilentFailureError = 1.0;
/// ... and one below this while it says it is lost a false alarm (off map is no false alarm: the
/// map does not cover the place, whatever the odometry's estimate is worth).
inline constexpr double kFalseAlarmError = 0.3;

/// A re-acquisition that took the estimate this much (m) farther from the truth is wrong.
inline constexpr double kWrongReacquisition = 0.5;

/// The increase of the localization error from one sample to the next, both measured in one
/// alignment: the later sample's local truth X_MR_truth, and the earlier sample's truth carried
/// back from it by the truth's own motion between them (X_WR_prev⁻¹ X_WR). The local truth's
/// alignment moves with the teaching sample it matches (far from the taught route, by metres
/// from one sample to the next), so the difference of two errors each in its own alignment would
/// count the alignment's move as the estimate's.
double ErrorIncrease(const core::Pose2& X_MR_prev, const core::Pose2& X_MR,
                     const core::Pose2& X_WR_prev, const core::Pose2& X_WR,
                     const core::Pose2& X_MR_truth);

/// m: a map switch whose truth lies this much farther from the taught trajectory of the map it
/// enters (the teaching drive's ground truth in that map) than from the nearest map's entered a
/// wrong map. (Against the nearest map's, not absolutely: a real drive strays from the taught
/// route by a metre or more.)
inline constexpr double kWrongSwitchDistance = 1.0;

struct LocalizerHealth {
  double lost_time_s = 0.0;  ///< each lost sample holds until the next
  /// s off map by the stack's own account (no map covered the place: odometry only), each such
  /// sample holding until the next
  double off_map_time_s = 0.0;
  /// With a truth: seconds with the error above kSilentFailureError while the stack said it was
  /// localized (neither lost nor off map), the longest such stretch, and seconds it said it was
  /// lost with the error below kFalseAlarmError. Each sample holds until the next.
  double silent_failure_time_s = 0.0;
  double longest_silent_failure_s = 0.0;
  double false_alarm_time_s = 0.0;
  /// Map switches (and wraps) into a map whose taught path the truth was not on (within
  /// kWrongSwitchDistance of the nearest map's): CountWrongSwitches, 0 without a truth.
  int wrong_switches = 0;
  int lost_spells = 0;       ///< times the localizer went from not lost to lost
  int reacquisitions = 0;    ///< recovery trials that replaced the belief
  /// Max over consecutive samples in the same map of |X_MR(k) − X_MR(k−1) ⊕ odometry step| (m):
  /// how far the estimate moved beyond the odometry's motion between them. NaN: < 2 samples.
  double max_jump_m = std::numeric_limits<double>::quiet_NaN();
  double max_jump_time_s = std::numeric_limits<double>::quiet_NaN();  ///< when it happened
  /// With a truth: the largest single-step increase of the localization error (m,
  /// EstimateSample::error_increase), and when; NaN without one.
  double max_error_increase_m = std::numeric_limits<double>::quiet_NaN();
  double max_error_increase_time_s = std::numeric_limits<double>::quiet_NaN();
  /// With a truth: re-acquisitions that took the estimate closer to it, and those that took it
  /// more than kWrongReacquisition farther away (over the sample that shows the update).
  int reacquisitions_closer = 0;
  int reacquisitions_wrong = 0;
};

LocalizerHealth ComputeLocalizerHealth(std::span<const EstimateSample> track,
                                       std::span<const LocalizerSample> updates);

/// The switches into a map whose taught trajectory (the teaching drive's ground truth in that
/// map) passes kWrongSwitchDistance farther from the switch's truth X_WR than the nearest map's.
int CountWrongSwitches(std::span<const SwitchRecord> switches, const TeachTrace& teach);

/// Over several runs: sums of the times and counts, the largest jump and error increase (and
/// their times, of the runs that had them).
LocalizerHealth CombineLocalizerHealth(std::span<const LocalizerHealth> runs);

}  // namespace retrace::bench
