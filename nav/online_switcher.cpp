#include "nav/online_switcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/config.hpp"
#include "core/segment.hpp"

namespace retrace::nav {

double OnlineSwitchingConfig::MaxMapLength() const {
  if (!(drift_budget > 0.0) || !(drift > 0.0)) return std::numeric_limits<double>::infinity();
  return drift_budget / drift;
}

double OnlineSwitchingConfig::MinMapLength() const {
  if (!(tolerance > 0.0)) return 0.0;
  if (!(drift > 0.0)) return std::numeric_limits<double>::infinity();
  return tolerance / drift;
}

void OnlineSwitchingConfig::Validate() const {
  core::RequirePositive("revisit_radius", revisit_radius);
  core::RequireNonNegative("window", window);
  core::RequireInRange("drift", drift, 0.0, 0.5);
  core::RequireNonNegative("drift_budget", drift_budget);
  core::RequireNonNegative("tolerance", tolerance);
  // A map must be able to outgrow the window it chooses its end in, or it would end where it
  // began.
  if (!(MaxMapLength() > window)) {
    throw core::ConfigError("drift_budget", "must allow maps longer than the switch window: " +
                                                core::FormatNumber(drift_budget) + " / drift " +
                                                core::FormatNumber(drift) + " = " +
                                                core::FormatNumber(MaxMapLength()) +
                                                " m of travel, window " +
                                                core::FormatNumber(window) + " m (0: no budget)");
  }
  // A loop the tolerance calls consistent must fit in a map.
  if (std::isfinite(MaxMapLength()) && !(MaxMapLength() > MinMapLength())) {
    const double shortest = std::round(MinMapLength() * 10.0) / 10.0;
    throw core::ConfigError("tolerance", "must be below the drift budget: loops up to " +
                                             core::FormatNumber(shortest) +
                                             " m would be consistent, but maps end after " +
                                             core::FormatNumber(MaxMapLength()) + " m");
  }
}

RevisitDetector::RevisitDetector(const OnlineSwitchingConfig& config) : config_(config) {
  config_.Validate();
  max_length_ = config_.MaxMapLength();
  step_ = RevisitSampleStep(config_.revisit_radius);
  lag_ = RevisitLag(config_.revisit_radius);
}

bool RevisitDetector::OnPose(const core::Pose2& X_OR) {
  const core::Vec2 p = X_OR.translation();
  if (has_pose_) travelled_ += (p - last_p_).norm();
  has_pose_ = true;
  last_p_ = p;
  if (!trail_.empty() && travelled_ - trail_.back().travelled < step_) return false;
  trail_.push_back({p, travelled_});

  // The trail's segments lying wholly more than lag_ behind, from the map's start.
  bool revisit = false;
  for (std::size_t i = 0; i + 1 < trail_.size(); ++i) {
    const Sample& a = trail_[i];
    const Sample& b = trail_[i + 1];
    if (b.travelled > travelled_ - lag_) break;
    const double loop_drift = config_.drift * (travelled_ - b.travelled);
    // A consistent loop needs no new map; its later samples lie closer still (the trail is in
    // the order driven), so the search ends here.
    if (loop_drift <= config_.tolerance) break;
    const double radius = config_.revisit_radius + loop_drift;
    if (core::SegmentDistance(p, a.p, b.p) < radius) {
      revisit = true;
      break;
    }
  }
  return revisit;
}

bool RevisitDetector::DriftBudgetReached() const {
  return travelled_ - map_start_ >= max_length_;
}

void RevisitDetector::StartMap(double travelled) {
  map_start_ = travelled;
  // Keep the trail from the last sample at or before the start, so the new map's trail begins
  // where the map does.
  auto first = std::upper_bound(trail_.begin(), trail_.end(), travelled,
                                [](double d, const Sample& s) { return d < s.travelled; });
  if (first != trail_.begin()) --first;
  trail_.erase(trail_.begin(), first);
}

}  // namespace retrace::nav
