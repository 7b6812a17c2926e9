#pragma once
// The closest point of a line segment to a point: the one kernel behind every point-to-segment
// distance in retrace (walls and pedestrians in sim, revisits in nav, taught paths in the
// metrics, polylines in viz). Path projection within an arc-length window
// (core/path_projection.hpp) is its windowed form.

#include <algorithm>

#include "core/pose2.hpp"

namespace retrace::core {

/// The point a + t (b - a) of the segment [a, b] closest to p, t in [0, 1]; a for a segment of
/// zero length.
inline Vec2 ClosestPointOnSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0) return a;
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return a + t * ab;
}

/// Distance (m) from p to the segment [a, b].
inline double SegmentDistance(const Vec2& p, const Vec2& a, const Vec2& b) {
  return (p - ClosestPointOnSegment(p, a, b)).norm();
}

/// Squared distance (m²) from p to the segment [a, b], for comparisons without a square root.
inline double SegmentDistanceSquared(const Vec2& p, const Vec2& a, const Vec2& b) {
  return (p - ClosestPointOnSegment(p, a, b)).squaredNorm();
}

}  // namespace retrace::core
