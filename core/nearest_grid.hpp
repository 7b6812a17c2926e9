#pragma once
// The one structure for exact nearest-item queries in the plane: a uniform grid over items that
// are segments (a polyline's, or points as zero-length segments), searched ring by ring outwards
// until no unvisited cell can hold a nearer item, optionally within a distance and a range of
// items. The metrics' taught path, a log's distance to the taught trajectory (PolylineDistance)
// and the revisit search along a route (core::PathIndex) use it.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "core/pose2.hpp"
#include "core/segment.hpp"

namespace retrace::core {

/// A uniform grid over items (segments, or points as zero-length segments) for exact nearest
/// queries: rings of cells around the query are searched until no unvisited cell can hold a
/// nearer item. The cells are stored sparsely (sorted (cell, item) pairs), so a grid of fine
/// cells over a long route costs memory in proportion to the route, not to its bounding box.
class NearestGrid {
 public:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  static constexpr double kInf = std::numeric_limits<double>::infinity();

  NearestGrid() = default;
  /// Item i is the segment a[i] b[i]; `cell` (m, > 0) is the cells' width.
  NearestGrid(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double cell);

  /// Cells for unbounded queries over these items: 1 m, or wider so that the items' bounding
  /// box is at most 1024 cells a side (a query far from everything visits few rings).
  static double CellForExtent(const std::vector<Vec2>& a, const std::vector<Vec2>& b);

  bool empty() const { return entries_.empty(); }

  /// The item i in [first, last) with the smallest dist2(i) (lowest index on ties) among those
  /// nearer than max_distance; kNone when there is none. dist2(i) is the squared distance (m²)
  /// from p to item i, +inf for an item to leave out.
  template <class Dist2>
  std::size_t Nearest(const Vec2& p, Dist2 dist2, double max_distance = kInf, std::size_t first = 0,
                      std::size_t last = kNone) const {
    if (entries_.empty() || !p.allFinite() || first >= last) return kNone;
    const std::int64_t cx = Cell(p.x());
    const std::int64_t cy = Cell(p.y());
    // Rings closer than the grid's edge hold nothing: start at the first one that touches it.
    const std::int64_t out_x = std::max({lo_x_ - cx, cx - hi_x_, std::int64_t{0}});
    const std::int64_t out_y = std::max({lo_y_ - cy, cy - hi_y_, std::int64_t{0}});
    const std::int64_t r_last = std::max({cx - lo_x_, hi_x_ - cx, cy - lo_y_, hi_y_ - cy});
    double best_d2 = max_distance * max_distance;
    std::size_t best = kNone;
    const auto visit = [&](std::int64_t x, std::int64_t y) {
      if (x < lo_x_ || x > hi_x_ || y < lo_y_ || y > hi_y_) return;
      const std::int64_t key = Key(x, y);
      for (auto e = std::lower_bound(entries_.begin(), entries_.end(), Entry{key, first});
           e != entries_.end() && e->cell == key && e->item < last; ++e) {
        const double d2 = dist2(e->item);
        if (d2 < best_d2 || (d2 == best_d2 && best != kNone && e->item < best)) {
          best_d2 = d2;
          best = e->item;
        }
      }
    };
    for (std::int64_t r = std::max(out_x, out_y); r <= r_last; ++r) {
      if (r == 0) {
        visit(cx, cy);
      } else {
        for (std::int64_t x = std::max(cx - r, lo_x_); x <= std::min(cx + r, hi_x_); ++x) {
          visit(x, cy - r);
          visit(x, cy + r);
        }
        for (std::int64_t y = std::max(cy - r + 1, lo_y_); y <= std::min(cy + r - 1, hi_y_); ++y) {
          visit(cx - r, y);
          visit(cx + r, y);
        }
      }
      // Every cell of ring r + 1 is at least r cells away from p (strictly: a tie there could
      // have a lower index).
      const double reach = static_cast<double>(r) * cell_;
      if (reach * reach > best_d2) break;
    }
    return best;
  }

 private:
  struct Entry {
    std::int64_t cell;
    std::size_t item;
    auto operator<=>(const Entry&) const = default;
  };
  std::int64_t Cell(double v) const;
  static std::int64_t Key(std::int64_t x, std::int64_t y) { return (x << 32) ^ (y & 0xffffffff); }

  double cell_ = 1.0;
  std::int64_t lo_x_ = 0, hi_x_ = -1, lo_y_ = 0, hi_y_ = -1;  // the cells in use, inclusive
  std::vector<Entry> entries_;  // sorted: a cell's items are a contiguous, ascending run
};

/// Distance (m) from p to the polyline through `points` with a NearestGrid over its segments
/// (consecutive duplicates give zero-length segments, which are points).
class PolylineDistance {
 public:
  explicit PolylineDistance(std::vector<Vec2> points) : points_(std::move(points)) {
    if (points_.size() == 1) points_.push_back(points_.front());
    if (points_.size() < 2) return;
    a_.assign(points_.begin(), points_.end() - 1);
    b_.assign(points_.begin() + 1, points_.end());
    grid_ = NearestGrid(a_, b_, NearestGrid::CellForExtent(a_, b_));
  }
  /// +inf without points.
  double operator()(const Vec2& p) const {
    const std::size_t i =
        grid_.Nearest(p, [&](std::size_t k) { return SegmentDistanceSquared(p, a_[k], b_[k]); });
    return i == NearestGrid::kNone ? std::numeric_limits<double>::infinity()
                                   : SegmentDistance(p, a_[i], b_[i]);
  }

 private:
  std::vector<Vec2> points_, a_, b_;
  NearestGrid grid_;
};

}  // namespace retrace::core
