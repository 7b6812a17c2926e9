#include "bench/metrics/localizer_health.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace retrace::bench {

double ErrorIncrease(const core::Pose2& X_MR_prev, const core::Pose2& X_MR,
                     const core::Pose2& X_WR_prev, const core::Pose2& X_WR,
                     const core::Pose2& X_MR_truth) {
  const core::Pose2 truth_prev = X_MR_truth * core::Between(X_WR, X_WR_prev);
  return (X_MR.translation() - X_MR_truth.translation()).norm() -
         (X_MR_prev.translation() - truth_prev.translation()).norm();
}

namespace {

// Keeps the larger of a running maximum (NaN: none yet) and v, with its time.
void KeepMax(double v, double time, double* max, double* max_time) {
  if (std::isfinite(v) && !(v <= *max)) {
    *max = v;
    *max_time = time;
  }
}

}  // namespace

LocalizerHealth ComputeLocalizerHealth(std::span<const EstimateSample> track,
                                       std::span<const LocalizerSample> updates) {
  LocalizerHealth h;
  double silent = 0.0;  // s of the silent failure going on
  for (std::size_t k = 0; k < track.size(); ++k) {
    const EstimateSample& s = track[k];
    if (s.lost && k + 1 < track.size()) h.lost_time_s += track[k + 1].time - s.time;
    if (s.off_map && k + 1 < track.size()) h.off_map_time_s += track[k + 1].time - s.time;
    if (k + 1 < track.size() && std::isfinite(s.error)) {
      const double dt = track[k + 1].time - s.time;
      const bool claims = !s.lost && !s.off_map;
      if (claims && s.error > kSilentFailureError) {
        h.silent_failure_time_s += dt;
        silent += dt;
        h.longest_silent_failure_s = std::max(h.longest_silent_failure_s, silent);
      } else {
        silent = 0.0;
      }
      if (s.lost && s.error < kFalseAlarmError) h.false_alarm_time_s += dt;
    }
    if (k == 0) {
      h.lost_spells += s.lost ? 1 : 0;
      continue;
    }
    const EstimateSample& prev = track[k - 1];
    h.lost_spells += s.lost && !prev.lost ? 1 : 0;
    if (s.map != prev.map) continue;  // a switch moves the frame, not the estimate
    const core::Pose2 predicted = prev.X_MR * core::Between(prev.X_OR, s.X_OR);
    KeepMax(core::Distance(predicted, s.X_MR), s.time, &h.max_jump_m, &h.max_jump_time_s);
    KeepMax(s.error_increase, s.time, &h.max_error_increase_m, &h.max_error_increase_time_s);
  }
  for (const LocalizerSample& u : updates) {
    if (!u.reacquired) continue;
    ++h.reacquisitions;
    // The first sample at or after the update shows it.
    const auto at = std::lower_bound(track.begin(), track.end(), u.time,
                                     [](const EstimateSample& e, double t) { return e.time < t; });
    if (at == track.end() || !std::isfinite(at->error_increase)) continue;
    h.reacquisitions_closer += at->error_increase < 0.0 ? 1 : 0;
    h.reacquisitions_wrong += at->error_increase > kWrongReacquisition ? 1 : 0;
  }
  return h;
}

namespace {

// m from p to the polyline through the poses' positions (+inf for none).
double DistanceToTrajectory(const core::Vec2& p, const std::vector<core::Pose2>& poses) {
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const core::Vec2 a = poses[i].translation();
    const core::Vec2 ab = poses[std::min(i + 1, poses.size() - 1)].translation() - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    nearest = std::min(nearest, (p - (a + t * ab)).norm());
  }
  return nearest;
}

}  // namespace

int CountWrongSwitches(std::span<const SwitchRecord> switches, const TeachTrace& teach) {
  int wrong = 0;
  for (const SwitchRecord& sw : switches) {
    if (sw.to < 0 || static_cast<std::size_t>(sw.to) >= teach.maps.size()) continue;
    const core::Vec2 p = sw.X_WR.translation();
    double nearest = std::numeric_limits<double>::infinity();
    for (const TeachMapTrace& map : teach.maps) {
      nearest = std::min(nearest, DistanceToTrajectory(p, map.X_WR));
    }
    const double entered = DistanceToTrajectory(p, teach.maps[static_cast<std::size_t>(sw.to)].X_WR);
    wrong += entered > nearest + kWrongSwitchDistance ? 1 : 0;
  }
  return wrong;
}

LocalizerHealth CombineLocalizerHealth(std::span<const LocalizerHealth> runs) {
  LocalizerHealth all;
  for (const LocalizerHealth& h : runs) {
    all.lost_time_s += h.lost_time_s;
    all.off_map_time_s += h.off_map_time_s;
    all.silent_failure_time_s += h.silent_failure_time_s;
    all.longest_silent_failure_s = std::max(all.longest_silent_failure_s, h.longest_silent_failure_s);
    all.false_alarm_time_s += h.false_alarm_time_s;
    all.wrong_switches += h.wrong_switches;
    all.lost_spells += h.lost_spells;
    all.reacquisitions += h.reacquisitions;
    all.reacquisitions_closer += h.reacquisitions_closer;
    all.reacquisitions_wrong += h.reacquisitions_wrong;
    KeepMax(h.max_jump_m, h.max_jump_time_s, &all.max_jump_m, &all.max_jump_time_s);
    KeepMax(h.max_error_increase_m, h.max_error_increase_time_s, &all.max_error_increase_m,
            &all.max_error_increase_time_s);
  }
  return all;
}

}  // namespace retrace::bench
