#include "core/path_index.hpp"

#include <algorithm>
#include <cmath>

#include "core/check.hpp"

namespace retrace::core {
namespace {

constexpr double kMaxCells = 1 << 18;  // pieces of path, so cells, at most (about)
constexpr double kMaxCellIndex = 1 << 30;

}  // namespace

PathIndex::PathIndex(std::span<const Vec2> points, std::span<const double> arc, double radius)
    : points_(points), arc_(arc), radius_(radius) {
  RETRACE_CHECK(points.size() == arc.size());
  RETRACE_CHECK(radius > 0.0 && std::isfinite(radius));
  const double length = arc.empty() ? 0.0 : arc.back();
  // A little wider than the radius, so that rounding in the pieces' ends cannot matter.
  cell_ = std::max(radius * (1.0 + 1e-6), length / kMaxCells);
  // Every segment is cut into pieces no longer than a cell; a piece's bounding box then covers
  // at most 2 x 2 cells, and the segment is listed in each of them. A point within the radius of
  // the segment lies within one cell of the cell of its closest point, which holds a piece.
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const Vec2 a = points[i];
    const Vec2 b = points[i + 1];
    const double len = (b - a).norm();
    const auto pieces = static_cast<std::size_t>(std::max(1.0, std::ceil(len / cell_)));
    for (std::size_t k = 0; k < pieces; ++k) {
      const Vec2 p0 = a + (b - a) * (static_cast<double>(k) / static_cast<double>(pieces));
      const Vec2 p1 = a + (b - a) * (static_cast<double>(k + 1) / static_cast<double>(pieces));
      for (std::int64_t ix = Cell(std::min(p0.x(), p1.x())); ix <= Cell(std::max(p0.x(), p1.x()));
           ++ix) {
        for (std::int64_t iy = Cell(std::min(p0.y(), p1.y())); iy <= Cell(std::max(p0.y(), p1.y()));
             ++iy) {
          entries_.push_back({Key(ix, iy), static_cast<std::uint32_t>(i)});
        }
      }
    }
  }
  std::sort(entries_.begin(), entries_.end());
  entries_.erase(std::unique(entries_.begin(), entries_.end()), entries_.end());
}

std::int64_t PathIndex::Cell(double v) const {
  // Clamped so that the cast is defined for any input; the cells of paths within
  // core::kMaxCoordinate never reach the clamp for cells above 10 µm.
  return static_cast<std::int64_t>(
      std::clamp(std::floor(v / cell_), -kMaxCellIndex, kMaxCellIndex));
}

std::int64_t PathIndex::Key(std::int64_t ix, std::int64_t iy) const {
  return (ix << 32) ^ (iy & 0xffffffff);
}

PathProjection PathIndex::Project(const Vec2& p, double s_lo, double s_hi) const {
  PathProjection best;
  best.s = s_lo;
  const SegmentRange range = SegmentsInWindow(arc_, s_lo, s_hi);
  if (range.first >= range.last) return best;
  std::vector<std::uint32_t> candidates;
  const std::int64_t cx = Cell(p.x());
  const std::int64_t cy = Cell(p.y());
  for (std::int64_t ix = cx - 1; ix <= cx + 1; ++ix) {
    for (std::int64_t iy = cy - 1; iy <= cy + 1; ++iy) {
      const std::int64_t key = Key(ix, iy);
      const Entry from{key, static_cast<std::uint32_t>(range.first)};
      for (auto j = std::lower_bound(entries_.begin(), entries_.end(), from);
           j != entries_.end() && j->cell == key && j->segment < range.last; ++j) {
        candidates.push_back(j->segment);
      }
    }
  }
  // In path order, as ProjectOntoPath visits them, so that ties resolve the same way.
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  for (const std::uint32_t i : candidates)
    ProjectOntoSegment(points_, arc_, i, p, s_lo, s_hi, &best);
  if (!(best.distance < radius_)) {
    best = PathProjection{};
    best.s = s_lo;
  }
  return best;
}

}  // namespace retrace::core
