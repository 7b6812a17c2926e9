#include "bench/local_truth.hpp"

#include <cmath>
#include <limits>

#include "core/angle.hpp"
#include "core/check.hpp"

namespace retrace::bench {

LocalTruth::LocalTruth(const TeachMapTrace& map) : map_(map) {
  RETRACE_CHECK(!map_.X_WR.empty() && map_.X_WR.size() == map_.X_MR.size());
  arc_.resize(map_.X_WR.size(), 0.0);
  for (std::size_t i = 1; i < arc_.size(); ++i) {
    arc_[i] = arc_[i - 1] + (map_.X_WR[i].translation() - map_.X_WR[i - 1].translation()).norm();
  }
}

core::Pose2 LocalTruth::InMap(const core::Pose2& X_WR) {
  const core::Vec2 p = X_WR.translation();
  auto nearest = [&](std::size_t lo, std::size_t hi) {
    std::size_t best = lo;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (std::size_t i = lo; i < hi; ++i) {
      const double d2 = (map_.X_WR[i].translation() - p).squaredNorm();
      if (d2 < best_d2) {
        best_d2 = d2;
        best = i;
      }
    }
    return std::pair{best, best_d2};
  };
  std::size_t lo = match_, hi = match_ + 1;
  while (lo > 0 && arc_[match_] - arc_[lo - 1] <= kWindow) --lo;
  while (hi < arc_.size() && arc_[hi] - arc_[match_] <= kWindow) ++hi;
  auto [best, d2] = nearest(lo, hi);
  if (d2 > kFallbackDistance * kFallbackDistance) best = nearest(0, arc_.size()).first;
  match_ = best;
  return map_.X_MR[best] * map_.X_WR[best].Inverse() * X_WR;
}

PoseError Compare(const core::Pose2& estimate, const core::Pose2& truth) {
  return {(estimate.translation() - truth.translation()).norm(),
          std::abs(core::AngleDiff(estimate.theta, truth.theta))};
}

}  // namespace retrace::bench
