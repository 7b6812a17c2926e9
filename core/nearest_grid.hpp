#pragma once
// The one structure for exact nearest-item queries in the plane: a uniform grid over items that
// are segments (a polyline's, or points as zero-length segments), searched ring by ring outwards
// until no unvisited cell can hold a nearer item. The metrics' taught path and a log's distance
// to the taught trajectory use it; core::PathIndex is the windowed projection along a path.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "core/check.hpp"
#include "core/pose2.hpp"
#include "core/segment.hpp"

namespace retrace::core {

// A uniform grid over items (segments, or points as zero-length segments) for exact nearest
// queries: rings of cells around the query are searched until no unvisited cell can hold a
// nearer item.
class NearestGrid {
 public:
  NearestGrid() = default;
  NearestGrid(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    RETRACE_CHECK(a.size() == b.size());
    if (a.empty()) return;
    Vec2 lo = a[0], hi = a[0];
    for (std::size_t i = 0; i < a.size(); ++i) {
      lo = lo.cwiseMin(a[i]).cwiseMin(b[i]);
      hi = hi.cwiseMax(a[i]).cwiseMax(b[i]);
    }
    const Vec2 extent = hi - lo;
    // At most 1024 cells a side; 1 m cells hold a few dozen samples of a taught path.
    cell_ = std::max(1.0, std::max(extent.x(), extent.y()) / 1024.0);
    origin_ = lo;
    nx_ = static_cast<long long>(extent.x() / cell_) + 1;
    ny_ = static_cast<long long>(extent.y() / cell_) + 1;
    // Each item goes into every cell of its bounding box that it passes through.
    std::vector<std::pair<std::size_t, std::size_t>> entries;  // (cell, item)
    entries.reserve(a.size() * 2);
    const double half_diagonal = 0.5 * std::sqrt(2.0) * cell_ * (1.0 + 1e-9);
    for (std::size_t i = 0; i < a.size(); ++i) {
      const long long x0 = CellX(std::min(a[i].x(), b[i].x()));
      const long long x1 = CellX(std::max(a[i].x(), b[i].x()));
      const long long y0 = CellY(std::min(a[i].y(), b[i].y()));
      const long long y1 = CellY(std::max(a[i].y(), b[i].y()));
      const bool single = x0 == x1 && y0 == y1;
      for (long long y = y0; y <= y1; ++y) {
        for (long long x = x0; x <= x1; ++x) {
          const Vec2 centre = origin_ + Vec2((static_cast<double>(x) + 0.5) * cell_,
                                             (static_cast<double>(y) + 0.5) * cell_);
          if (single ||
              SegmentDistanceSquared(centre, a[i], b[i]) <= half_diagonal * half_diagonal) {
            entries.emplace_back(static_cast<std::size_t>(y * nx_ + x), i);
          }
        }
      }
    }
    std::stable_sort(entries.begin(), entries.end(),
                     [](const auto& l, const auto& r) { return l.first < r.first; });
    start_.assign(static_cast<std::size_t>(nx_ * ny_) + 1, 0);
    for (const auto& [c, i] : entries) ++start_[c + 1];
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    items_.reserve(entries.size());
    for (const auto& [c, i] : entries) items_.push_back(i);
  }

  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  static constexpr double kInf = std::numeric_limits<double>::infinity();

  bool empty() const { return items_.empty(); }

  // The item with the smallest dist2(item) (lowest index on ties), kNone when empty.
  template <class Dist2>
  std::size_t Nearest(const Vec2& p, Dist2 dist2) const {
    if (items_.empty() || !p.allFinite()) return kNone;
    const long long cx = CellX(p.x());
    const long long cy = CellY(p.y());
    // Rings closer than the grid's edge hold nothing: start at the first one that touches it.
    const long long out_x = cx < 0 ? -cx : (cx >= nx_ ? cx - nx_ + 1 : 0);
    const long long out_y = cy < 0 ? -cy : (cy >= ny_ ? cy - ny_ + 1 : 0);
    const long long r_first = std::max(out_x, out_y);
    const long long r_last = std::max({cx, nx_ - 1 - cx, cy, ny_ - 1 - cy});
    double best_d2 = kInf;
    std::size_t best = kNone;
    auto visit = [&](long long x, long long y) {
      if (x < 0 || x >= nx_ || y < 0 || y >= ny_) return;
      const std::size_t c = static_cast<std::size_t>(y * nx_ + x);
      for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) {
        const std::size_t i = items_[k];
        const double d2 = dist2(i);
        if (d2 < best_d2 || (d2 == best_d2 && i < best)) {
          best_d2 = d2;
          best = i;
        }
      }
    };
    for (long long r = r_first; r <= r_last; ++r) {
      if (r == 0) {
        visit(cx, cy);
      } else {
        for (long long x = std::max(cx - r, 0LL); x <= std::min(cx + r, nx_ - 1); ++x) {
          visit(x, cy - r);
          visit(x, cy + r);
        }
        for (long long y = std::max(cy - r + 1, 0LL); y <= std::min(cy + r - 1, ny_ - 1); ++y) {
          visit(cx - r, y);
          visit(cx + r, y);
        }
      }
      // Every cell of ring r + 1 is at least r cells away from p.
      const double reach = static_cast<double>(r) * cell_;
      if (best != kNone && best_d2 <= reach * reach) break;
    }
    return best;
  }

 private:
  long long CellX(double x) const { return ToCell((x - origin_.x()) / cell_); }
  long long CellY(double y) const { return ToCell((y - origin_.y()) / cell_); }
  static long long ToCell(double v) {
    return static_cast<long long>(std::floor(std::clamp(v, -1e12, 1e12)));
  }

  Vec2 origin_{0.0, 0.0};
  double cell_ = 1.0;
  long long nx_ = 0;
  long long ny_ = 0;
  std::vector<std::size_t> start_;  // items of cell c: items_[start_[c], start_[c + 1])
  std::vector<std::size_t> items_;
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
    grid_ = NearestGrid(a_, b_);
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
