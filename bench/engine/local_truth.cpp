#include "bench/engine/local_truth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/angle.hpp"
#include "core/check.hpp"

namespace retrace::bench {

LocalTruth::LocalTruth(const TeachMapTrace& map, double window, double fallback_distance)
    : map_(map), window_(window), fallback_distance_(fallback_distance) {
  RETRACE_CHECK(!map_.X_WR.empty() && map_.X_WR.size() == map_.X_MR.size());
  arc_.resize(map_.X_WR.size(), 0.0);
  for (std::size_t i = 1; i < arc_.size(); ++i) {
    arc_[i] = arc_[i - 1] + (map_.X_WR[i].translation() - map_.X_WR[i - 1].translation()).norm();
  }
}

std::size_t LocalTruth::Nearest(const core::Vec2& p, std::size_t lo, std::size_t hi,
                                double* d2) const {
  std::size_t best = lo;
  *d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = lo; i < hi; ++i) {
    const double e = (map_.X_WR[i].translation() - p).squaredNorm();
    if (e < *d2) {
      *d2 = e;
      best = i;
    }
  }
  return best;
}

core::Pose2 LocalTruth::InMap(const core::Pose2& X_WR) {
  const core::Vec2 p = X_WR.translation();
  const auto lo = std::lower_bound(arc_.begin(), arc_.end(), arc_[match_] - window_);
  const auto hi = std::upper_bound(arc_.begin(), arc_.end(), arc_[match_] + window_);
  double d2 = 0.0;
  std::size_t best = Nearest(p, static_cast<std::size_t>(lo - arc_.begin()),
                             static_cast<std::size_t>(hi - arc_.begin()), &d2);
  if (d2 > fallback_distance_ * fallback_distance_) {
    double global_d2 = 0.0;
    const std::size_t global = Nearest(p, 0, arc_.size(), &global_d2);
    if (global_d2 < d2) best = global;
  }
  match_ = best;
  return map_.X_MR[best] * map_.X_WR[best].Inverse() * X_WR;
}

PoseError Compare(const core::Pose2& estimate, const core::Pose2& truth) {
  return {(estimate.translation() - truth.translation()).norm(),
          std::abs(core::AngleDiff(estimate.theta, truth.theta))};
}

}  // namespace retrace::bench
