#include "bench/engine/local_truth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "core/angle.hpp"
#include "core/check.hpp"
#include "core/path_projection.hpp"

namespace retrace::bench {

LocalTruth::Path::Path(std::vector<core::Vec2> points, double radius)
    : positions(std::move(points)),
      arc(core::CumulativeArcLength(positions)),
      index(positions, arc, radius) {}

namespace {

std::vector<core::Vec2> PositionsOf(const TeachMapTrace& map) {
  std::vector<core::Vec2> positions;
  positions.reserve(map.X_WR.size());
  for (const core::Pose2& X : map.X_WR) positions.push_back(X.translation());
  return positions;
}

}  // namespace

LocalTruth::LocalTruth(const TeachMapTrace& map, double window, double fallback_distance)
    : map_(&map), window_(window), fallback_distance_(fallback_distance) {
  RETRACE_CHECK(!map_->X_WR.empty() && map_->X_WR.size() == map_->X_MR.size());
  path_ = std::make_shared<const Path>(PositionsOf(map), fallback_distance);
}

std::size_t LocalTruth::Nearest(const core::Vec2& p, std::size_t lo, std::size_t hi,
                                double* d2) const {
  const std::vector<core::Vec2>& positions = path_->positions;
  std::size_t best = lo;
  *d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = lo; i < hi; ++i) {
    const double e = (positions[i] - p).squaredNorm();
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
  // Farther than fallback_distance the index answers +inf; the global search below then takes
  // the nearest sample, as it would have replaced the projection's.
  const std::vector<double>& arc = path_->arc;
  const core::PathProjection near =
      path_->index.Project(p, arc[match_] - window_, arc[match_] + window_);
  std::size_t best = match_;
  double d2 = std::numeric_limits<double>::infinity();
  if (std::isfinite(near.distance)) {
    const std::size_t i = near.segment;
    best = near.s - arc[i] <= arc[i + 1] - near.s ? i : i + 1;
    d2 = (path_->positions[best] - p).squaredNorm();
  }
  if (!(near.distance <= fallback_distance_)) {
    double global_d2 = 0.0;
    const std::size_t global = Nearest(p, 0, arc.size(), &global_d2);
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

std::size_t LocalTruthAcrossMaps::NearestMap(const core::Pose2& X_WR) const {
  // Where two maps' paths pass the place (a street the route drove twice, a crossing), the one
  // driven along the robot's heading, either way, is where it is: a teaching sample counts as
  // kHeadingCost m farther for a heading across the robot's.
  constexpr double kHeadingCost = 1.0;
  std::size_t best = 0;
  double best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < teach_.maps.size(); ++k) {
    for (const core::Pose2& X : teach_.maps[k].X_WR) {
      const double across = 1.0 - std::abs(std::cos(core::AngleDiff(X.theta, X_WR.theta)));
      const double cost = (X.translation() - X_WR.translation()).norm() + kHeadingCost * across;
      if (cost < best_cost) {
        best_cost = cost;
        best = k;
      }
    }
  }
  return best;
}

}  // namespace retrace::bench
