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
#include "core/nearest_grid.hpp"
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
    grid_ = core::NearestGrid(a, b, core::NearestGrid::CellForExtent(a, b));
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
  core::NearestGrid grid_;
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
