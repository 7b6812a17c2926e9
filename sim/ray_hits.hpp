#pragma once
// The exact ray-primitive hit tests of the RayCaster, inline for its inner loops. Every cast
// (single rays, fans, wedges of rays) computes a hit with these same operations, so they all agree
// bit for bit with each other and with testing every primitive.

#include <cmath>
#include <limits>

namespace retrace::sim::ray_hits {

inline constexpr double kMiss = std::numeric_limits<double>::infinity();

// Ray origin + t * dir against segment a + s * d, s in [0, 1]. Cramer's rule on
// t * dir - s * d = a - origin; the range checks compare numerators against the denominator's
// sign so that only accepted hits pay for the division.
inline double SegmentHit(double ox, double oy, double ux, double uy, double ax, double ay,
                         double dx, double dy) {
  const double denom = ux * dy - uy * dx;
  const double wx = ax - ox;
  const double wy = ay - oy;
  const double nt = wx * dy - wy * dx;
  const double ns = wx * uy - wy * ux;
  if (denom > 0.0) {
    if (nt < 0.0 || ns < 0.0 || ns > denom) return kMiss;
  } else if (denom < 0.0) {
    if (nt > 0.0 || ns > 0.0 || ns < denom) return kMiss;
  } else {
    return kMiss;  // parallel or collinear: a grazing ray
  }
  return nt / denom + 0.0;  // + 0.0 turns a -0.0 into +0.0
}

// Ray origin + t * dir (|dir|^2 = uu) against the boundary of a circle (centre c, radius^2 r2).
// Roots of uu t^2 - 2 b t + cc = 0; the near root is written as cc / (b + sqrt(D)) to avoid
// cancellation, the far one (origin inside) likewise by its sign of b.
inline double CircleHit(double ox, double oy, double ux, double uy, double uu, double cx, double cy,
                        double r2) {
  const double wx = cx - ox;
  const double wy = cy - oy;
  const double b = wx * ux + wy * uy;
  const double cc = wx * wx + wy * wy - r2;
  if (cc > 0.0) {  // outside
    if (b <= 0.0) return kMiss;
    const double disc = b * b - uu * cc;
    if (disc < 0.0) return kMiss;
    return cc / (b + std::sqrt(disc));
  }
  if (cc == 0.0) return 0.0;  // on the boundary
  const double root = std::sqrt(b * b - uu * cc);
  return b >= 0.0 ? (b + root) / uu : cc / (b - root);
}

}  // namespace retrace::sim::ray_hits
