#pragma once
// Projecting a point onto a polyline within a window of arc length: the one routine behind
// every "how far along the path is the robot" in retrace — the teacher's and the path
// follower's progress, the scripted events' progress along the route, the metrics' match on
// the taught path and the local truth's teaching sample. ForwardProgress is its common use: a
// progress that only moves forward, searched a short way ahead, so that a route that comes back
// near itself (a loop) is followed in order instead of jumping to a later pass.

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "core/pose2.hpp"

namespace retrace::core {

/// Where a point projects onto a polyline.
struct PathProjection {
  double s = 0.0;  ///< m, arc length of the closest point
  double distance = std::numeric_limits<double>::infinity();  ///< m, from the point to it
  std::size_t segment = 0;  ///< it lies on the segment from point `segment` to `segment + 1`
};

/// Arc length at each point of a polyline (m): 0, then the running sum of the segment lengths.
std::vector<double> CumulativeArcLength(std::span<const Vec2> points);

/// The closest point to p among the points of the polyline through `points` whose arc length
/// lies in [s_lo, s_hi]; arc[i] is the arc length at points[i] (non-decreasing, same size).
/// Ties keep the earlier point; segments shorter than 1 nm are skipped. When no segment reaches
/// into the window (or the polyline has fewer than two points): distance +inf, s = s_lo.
PathProjection ProjectOntoPath(std::span<const Vec2> points, std::span<const double> arc,
                               const Vec2& p, double s_lo, double s_hi);

/// ProjectOntoPath's step for one segment: if the point of segment `i` (from points[i] to
/// points[i + 1]) closest to p within the arc window [s_lo, s_hi] is closer than `best`, makes
/// it the best. Segments shorter than 1 nm are skipped.
void ProjectOntoSegment(std::span<const Vec2> points, std::span<const double> arc, std::size_t i,
                        const Vec2& p, double s_lo, double s_hi, PathProjection* best);

/// The segments ProjectOntoPath considers for the window [s_lo, s_hi]: i in [first, last).
struct SegmentRange {
  std::size_t first = 0;
  std::size_t last = 0;
};
SegmentRange SegmentsInWindow(std::span<const double> arc, double s_lo, double s_hi);

/// A progress (m of arc length) along a polyline that only moves forward.
class ForwardProgress {
 public:
  /// Moves to the closest point of the polyline (as for ProjectOntoPath) in [progress, s_hi]
  /// if that lies ahead, never back; returns the progress.
  double Advance(std::span<const Vec2> points, std::span<const double> arc, const Vec2& p,
                 double s_hi);
  /// Moves to arc length s if that lies ahead (a stop reached, a path restarted elsewhere).
  void MoveTo(double s);
  double value() const { return value_; }

 private:
  double value_ = 0.0;
};

}  // namespace retrace::core
