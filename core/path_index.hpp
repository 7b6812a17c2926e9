#pragma once
// Windowed projection onto a long path within a radius, answered from a core::NearestGrid over
// the path's segments, so that a query looks at the few segments near the point instead of the
// whole path (checking the switch points of a 100 km route is linear in its length, not
// quadratic).

#include <span>
#include <vector>

#include "core/nearest_grid.hpp"
#include "core/path_projection.hpp"

namespace retrace::core {

class PathIndex {
 public:
  /// Indexes the polyline through `points` (arc as from CumulativeArcLength, same size; both
  /// must outlive the index) for queries within `radius` (m, > 0). The cells are at least
  /// `radius` wide, and wider when the path is so long that it would need more than 2^18 of them.
  PathIndex(std::span<const Vec2> points, std::span<const double> arc, double radius);

  /// ProjectOntoPath(points, arc, p, s_lo, s_hi) when its closest point lies within the radius
  /// (the same s, distance and segment); otherwise distance +inf and s = s_lo.
  PathProjection Project(const Vec2& p, double s_lo, double s_hi) const;

  double cell_size() const { return cell_; }

 private:
  std::span<const Vec2> points_;
  std::span<const double> arc_;
  double radius_ = 0.0;
  double cell_ = 0.0;
  NearestGrid grid_;  // item i: the segment from point i to point i + 1
};

}  // namespace retrace::core
