#include "bench/engine/local_truth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/angle.hpp"
#include "core/check.hpp"
#include "core/path_projection.hpp"

namespace retrace::bench {

LocalTruth::LocalTruth(const TeachMapTrace& map, double window, double fallback_distance)
    : map_(&map), window_(window), fallback_distance_(fallback_distance) {
  RETRACE_CHECK(!map_->X_WR.empty() && map_->X_WR.size() == map_->X_MR.size());
  positions_.reserve(map_->X_WR.size());
  for (const core::Pose2& X : map_->X_WR) positions_.push_back(X.translation());
  arc_ = core::CumulativeArcLength(positions_);
}

std::size_t LocalTruth::Nearest(const core::Vec2& p, std::size_t lo, std::size_t hi,
                                double* d2) const {
  std::size_t best = lo;
  *d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = lo; i < hi; ++i) {
    const double e = (positions_[i] - p).squaredNorm();
    if (e < *d2) {
      *d2 = e;
      best = i;
    }
  }
  return best;
}

core::Pose2 LocalTruth::InMap(const core::Pose2& X_WR) {
  const core::Vec2 p = X_WR.translation();
  // The teaching sample at the projection onto the segment's path near the last match: the
  // nearer end, by arc length, of the piece of path it falls on.
  const core::PathProjection near =
      core::ProjectOntoPath(positions_, arc_, p, arc_[match_] - window_, arc_[match_] + window_);
  std::size_t best = match_;
  double d2 = std::numeric_limits<double>::infinity();
  if (std::isfinite(near.distance)) {
    const std::size_t i = near.segment;
    best = near.s - arc_[i] <= arc_[i + 1] - near.s ? i : i + 1;
    d2 = (positions_[best] - p).squaredNorm();
  }
  if (!(near.distance <= fallback_distance_)) {
    double global_d2 = 0.0;
    const std::size_t global = Nearest(p, 0, arc_.size(), &global_d2);
    if (global_d2 < d2) best = global;
  }
  match_ = best;
  return map_->X_MR[best] * map_->X_WR[best].Inverse() * X_WR;
}

PoseError Compare(const core::Pose2& estimate, const core::Pose2& truth) {
  return {(estimate.translation() - truth.translation()).norm(),
          std::abs(core::AngleDiff(estimate.theta, truth.theta))};
}

LocalTruthAcrossMaps::LocalTruthAcrossMaps(const TeachTrace& teach, double window,
                                           double fallback_distance)
    : teach_(teach),
      window_(window),
      fallback_distance_(fallback_distance),
      current_(teach.maps.at(0), window, fallback_distance) {}

void LocalTruthAcrossMaps::Enter(std::size_t map) {
  current_ = LocalTruth(teach_.maps.at(map), window_, fallback_distance_);
}

}  // namespace retrace::bench
