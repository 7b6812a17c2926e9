#include "nav/online_switcher.hpp"

#include <algorithm>

#include "core/config.hpp"

namespace retrace::nav {
namespace {

// How far back (in revisit radii) a part of the trail must lie to count as a revisit; closer
// parts are the road just driven, bent by a turn. As in bench/engine/switch_points.cpp.
constexpr double kRevisitLagFactor = 3.0;

// Distance from p to the segment [a, b].
double SegmentDistance(const core::Vec2& p, const core::Vec2& a, const core::Vec2& b) {
  const core::Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

}  // namespace

void OnlineSwitchingConfig::Validate() const {
  core::RequirePositive("revisit_radius", revisit_radius);
  core::RequireNonNegative("window", window);
  core::RequireInRange("drift", drift, 0.0, 0.5);
}

RevisitDetector::RevisitDetector(const OnlineSwitchingConfig& config) : config_(config) {
  config_.Validate();
  // The sampling of CheckSwitchPoints: fine enough that a revisit cannot slip between samples.
  step_ = std::clamp(config_.revisit_radius / 8.0, 0.05, 0.5);
  lag_ = kRevisitLagFactor * config_.revisit_radius;
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
    const double radius = config_.revisit_radius + config_.drift * (travelled_ - b.travelled);
    if (SegmentDistance(p, a.p, b.p) < radius) {
      revisit = true;
      break;
    }
  }
  return revisit;
}

void RevisitDetector::StartMap(double travelled) {
  // Keep the trail from the last sample at or before the start, so the new map's trail begins
  // where the map does.
  auto first = std::upper_bound(trail_.begin(), trail_.end(), travelled,
                                [](double d, const Sample& s) { return d < s.travelled; });
  if (first != trail_.begin()) --first;
  trail_.erase(trail_.begin(), first);
}

}  // namespace retrace::nav
