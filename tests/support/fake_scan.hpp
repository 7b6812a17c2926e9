#pragma once
// Fake LiDAR scans for the navigation tests: exact ray casting against simple primitives (in
// W), optional range noise, REP-117 readings (+inf: no return or beyond range_max, -inf:
// closer than range_min). The simulator's LiDAR is not used here: nav's tests must not depend
// on sim.
//
//   const core::LaserScan scan = testing::FakeScan(testing::ScanSpec{}, X_WL,
//       [&](const Vec2& o, const Vec2& d) { return testing::NearestSegment(o, d, walls); });

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "core/angle.hpp"
#include "core/laser_scan.hpp"
#include "core/pose2.hpp"

namespace retrace::testing {

using core::Vec2;

inline constexpr double kNoHit = std::numeric_limits<double>::infinity();

struct Segment {
  Vec2 a;
  Vec2 b;
};
/// A solid axis-aligned rectangle [x0, x1] × [y0, y1].
struct Rect {
  double x0, y0, x1, y1;
};
struct Circle {
  Vec2 c;
  double r;
};

/// Distance (m) from o along the unit vector d to the segment; +inf if the ray misses it.
inline double RaySegment(const Vec2& o, const Vec2& d, const Segment& s) {
  const Vec2 e = s.b - s.a;
  const double denom = d.x() * e.y() - d.y() * e.x();
  if (std::abs(denom) < 1e-12) return kNoHit;  // parallel
  const Vec2 w = s.a - o;
  const double t = (w.x() * e.y() - w.y() * e.x()) / denom;
  const double u = (w.x() * d.y() - w.y() * d.x()) / denom;
  if (t < 0.0 || u < 0.0 || u > 1.0) return kNoHit;
  return t;
}

/// Distance (m) from o along the unit vector d into the rectangle (0 from inside); +inf on a miss.
inline double RayRect(const Vec2& o, const Vec2& d, const Rect& r) {
  double t0 = 0.0, t1 = kNoHit;
  const double lo[2] = {r.x0, r.y0}, hi[2] = {r.x1, r.y1};
  for (int k = 0; k < 2; ++k) {
    if (std::abs(d[k]) < 1e-15) {
      if (o[k] < lo[k] || o[k] > hi[k]) return kNoHit;
      continue;
    }
    double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1 ? t0 : kNoHit;
}

/// Distance (m) from o along the unit vector d to the circle's edge; +inf on a miss.
inline double RayCircle(const Vec2& o, const Vec2& d, const Circle& c) {
  const Vec2 m = o - c.c;
  const double b = m.dot(d), cc = m.squaredNorm() - c.r * c.r;
  const double disc = b * b - cc;
  if (disc < 0.0) return kNoHit;
  const double t = -b - std::sqrt(disc);
  return t >= 0.0 ? t : kNoHit;
}

/// The nearest of `segments` along the ray; +inf when none is hit.
inline double NearestSegment(const Vec2& o, const Vec2& d, const std::vector<Segment>& segments) {
  double r = kNoHit;
  for (const Segment& s : segments) r = std::min(r, RaySegment(o, d, s));
  return r;
}

/// The beams of a fake LiDAR (default: a Hokuyo UTM-30LX, 270°, 1081 beams, 0.05–30 m).
struct ScanSpec {
  int beams = 1081;
  double fov = core::DegToRad(270.0);  ///< rad; a full circle spaces the beams without overlap
  double range_min = 0.05;
  double range_max = 30.0;
};

/// A scan from the LiDAR at X_WL: beam i's true range is range_at(origin, direction) (m, +inf
/// for nothing); `noise` (optional) turns a true range into a measured one and is called for
/// every beam in order, so that its random draws do not depend on what was hit.
template <class RangeAt>
core::LaserScan FakeScan(const ScanSpec& spec, const core::Pose2& X_WL, RangeAt range_at,
                         const std::function<double(double)>& noise = {}) {
  core::LaserScan scan;
  const bool full = spec.fov >= 2.0 * core::kPi - 1e-9;
  scan.angle_increment = spec.fov / (full ? spec.beams : spec.beams - 1);
  scan.angle_min = full ? -core::kPi : -0.5 * spec.fov;
  scan.range_min = spec.range_min;
  scan.range_max = spec.range_max;
  scan.ranges.resize(static_cast<std::size_t>(spec.beams));
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double a = X_WL.theta + scan.Angle(i);
    double r = range_at(X_WL.translation(), Vec2(std::cos(a), std::sin(a)));
    if (noise) r = noise(r);
    const float inf = std::numeric_limits<float>::infinity();
    scan.ranges[i] = !(r <= spec.range_max) ? inf
                     : r < spec.range_min   ? -inf
                                            : static_cast<float>(r);
  }
  return scan;
}

}  // namespace retrace::testing
