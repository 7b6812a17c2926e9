#pragma once
// A uniform grid over a polyline's segments, for ProjectOntoPath queries that only care about
// points within a radius: each query then costs the segments near the point instead of the whole
// path (checking the switch points of a 100 km route is linear in its length, not quadratic).

#include <cstdint>
#include <span>
#include <vector>

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
  std::int64_t Key(std::int64_t ix, std::int64_t iy) const;
  std::int64_t Cell(double v) const;

  std::span<const Vec2> points_;
  std::span<const double> arc_;
  double radius_ = 0.0;
  double cell_ = 0.0;
  /// (cell, segment) for every segment (index of its first point) reaching into a cell, sorted:
  /// a cell's segments are a contiguous, ascending run.
  struct Entry {
    std::int64_t cell;
    std::uint32_t segment;
    auto operator<=>(const Entry&) const = default;
  };
  std::vector<Entry> entries_;
};

}  // namespace retrace::core
