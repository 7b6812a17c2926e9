#include "core/path_index.hpp"

#include <algorithm>
#include <cmath>

#include "core/check.hpp"

namespace retrace::core {
namespace {

constexpr double kMaxCells = 1 << 18;  // pieces of path, so cells, at most (about)

}  // namespace

PathIndex::PathIndex(std::span<const Vec2> points, std::span<const double> arc, double radius)
    : points_(points), arc_(arc), radius_(radius) {
  RETRACE_CHECK(points.size() == arc.size());
  RETRACE_CHECK(radius > 0.0 && std::isfinite(radius));
  const double length = arc.empty() ? 0.0 : arc.back();
  // A little wider than the radius, so that rounding in the pieces' ends cannot matter: a query
  // then looks at its own cell and the eight around it.
  cell_ = std::max(radius * (1.0 + 1e-6), length / kMaxCells);
  std::vector<Vec2> a, b;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    a.push_back(points[i]);
    b.push_back(points[i + 1]);
  }
  grid_ = NearestGrid(a, b, cell_);
}

PathProjection PathIndex::Project(const Vec2& p, double s_lo, double s_hi) const {
  PathProjection none;
  none.s = s_lo;
  const SegmentRange range = SegmentsInWindow(arc_, s_lo, s_hi);
  // The windowed projection onto segment i, as ProjectOntoPath computes it.
  const auto project = [&](std::size_t i) {
    PathProjection one = none;
    ProjectOntoSegment(points_, arc_, i, p, s_lo, s_hi, &one);
    return one;
  };
  const std::size_t i = grid_.Nearest(
      p,
      [&](std::size_t k) {
        const double d = project(k).distance;
        return d * d;
      },
      radius_, range.first, range.last);
  return i == NearestGrid::kNone ? none : project(i);
}

}  // namespace retrace::core
