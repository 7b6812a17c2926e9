#pragma once
// The taught path of the metrics: the polyline through the teaching drive's ground-truth
// positions, with exact nearest-segment queries (a uniform grid) and the windowed, monotone
// progress tracking along it that the tracking error, the repeatability's lateral offsets and
// the progress use.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "bench/engine/metrics_config.hpp"
#include "bench/metrics/metrics.hpp"
#include "core/check.hpp"
#include "core/path_projection.hpp"
#include "core/pose2.hpp"
#include "core/segment.hpp"

namespace retrace::bench::internal {

using core::Pose2;
using core::Vec2;

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
// Consecutive taught positions closer than this are one vertex (m): a standing robot would
// otherwise give zero-length segments without a direction.
inline constexpr double kDuplicateDistance = 1e-9;


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
          if (single || core::SegmentDistanceSquared(centre, a[i], b[i]) <= half_diagonal * half_diagonal) {
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

struct Projection {
  double distance = kInf;  // m, to the closest point of the path
  double s = 0.0;          // m, arc length of the foot point (beyond the ends: extended)
  double lateral = 0.0;    // m, signed offset, > 0 left of the path direction
};

// The taught path: the polyline through the teaching drive's ground-truth positions.
class TaughtPath {
 public:
  explicit TaughtPath(const std::vector<Pose2>& X_WR) {
    for (const Pose2& X : X_WR) {
      const Vec2 p = X.translation();
      if (points_.empty() || (p - points_.back()).norm() > kDuplicateDistance) {
        points_.push_back(p);
      }
    }
    arc_ = core::CumulativeArcLength(points_);
    std::vector<Vec2> a, b;
    for (std::size_t i = 0; i < segments(); ++i) {
      a.push_back(points_[i]);
      b.push_back(points_[End(i)]);
    }
    grid_ = NearestGrid(a, b);
  }

  bool empty() const { return points_.empty(); }
  double length() const { return arc_.empty() ? 0.0 : arc_.back(); }

  // Exact distance from p to the path (m); NaN for an empty path.
  double Distance(const Vec2& p) const {
    const std::size_t i = grid_.Nearest(p, [&](std::size_t k) { return Dist2(k, p); });
    return i == kNone ? kMetricNaN : std::sqrt(Dist2(i, p));
  }

  Projection ProjectGlobal(const Vec2& p) const {
    const std::size_t i = grid_.Nearest(p, [&](std::size_t k) { return Dist2(k, p); });
    return i == kNone ? Projection{} : Finish(i, p);
  }

  // The points and arc lengths of the polyline (duplicates dropped).
  const std::vector<Vec2>& points() const { return points_; }
  const std::vector<double>& arc() const { return arc_; }

  // The projection onto segment i (extended beyond the ends), with its signed lateral offset.
  Projection Finish(std::size_t i, const Vec2& p) const {
    const Vec2& a = points_[i];
    const Vec2 d = points_[End(i)] - a;
    const double len = d.norm();
    Projection out;
    out.distance = std::sqrt(Dist2(i, p));
    if (len == 0.0) {
      out.s = arc_[i];
      return out;
    }
    const Vec2 u = d / len;
    const Vec2 ap = p - a;
    const double t_raw = ap.dot(u);  // m along the segment
    const double cross = u.x() * ap.y() - u.y() * ap.x();
    const bool before_start = i == 0 && t_raw < 0.0;
    const bool after_end = i + 1 == segments() && t_raw > len;
    if (before_start || after_end || (t_raw >= 0.0 && t_raw <= len)) {
      // On the segment, or on the extension of the first / last one.
      out.s = arc_[i] + t_raw;
      out.lateral = cross;
    } else {
      // Closest to an inner vertex (outside of a corner): the side from the segment chosen.
      out.s = arc_[i] + std::clamp(t_raw, 0.0, len);
      out.lateral = std::copysign(out.distance, cross);
    }
    return out;
  }

 private:
  // Segment i runs from point i to point i + 1; a one-point path has one zero-length segment.
  std::size_t segments() const { return points_.size() <= 1 ? points_.size() : points_.size() - 1; }
  std::size_t End(std::size_t i) const { return std::min(i + 1, points_.size() - 1); }
  double Dist2(std::size_t i, const Vec2& p) const {
    return core::SegmentDistanceSquared(p, points_[i], points_[End(i)]);
  }

  std::vector<Vec2> points_;
  std::vector<double> arc_;
  NearestGrid grid_;
};

// Progress along the taught path: the projection (core/path_projection.hpp) within a window
// around the previous match, the whole path only when the window's best is far.
class PathTracker {
 public:
  PathTracker(const TaughtPath& path, const MetricsConfig& config) : path_(path), config_(config) {}

  Projection Track(const Vec2& p) {
    const double centre = std::clamp(s_prev_, 0.0, path_.length());
    const core::PathProjection near =
        core::ProjectOntoPath(path_.points(), path_.arc(), p, centre - config_.match_window,
                              centre + config_.match_window);
    Projection best;
    if (std::isfinite(near.distance)) best = path_.Finish(near.segment, p);
    if (!(near.distance <= config_.match_fallback_distance)) {
      const Projection global = path_.ProjectGlobal(p);
      if (global.distance < best.distance) best = global;
    }
    s_prev_ = best.s;
    return best;
  }

 private:
  const TaughtPath& path_;
  const MetricsConfig& config_;
  double s_prev_ = 0.0;
};

}  // namespace retrace::bench::internal
