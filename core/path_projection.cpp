#include "core/path_projection.hpp"

#include <algorithm>

#include "core/check.hpp"

namespace retrace::core {
namespace {

constexpr double kTinyLength = 1e-9;  // m: a segment shorter than this has no direction

}  // namespace

std::vector<double> CumulativeArcLength(std::span<const Vec2> points) {
  std::vector<double> arc(points.size(), 0.0);
  for (std::size_t i = 1; i < points.size(); ++i) {
    arc[i] = arc[i - 1] + (points[i] - points[i - 1]).norm();
  }
  return arc;
}

void ProjectOntoSegment(std::span<const Vec2> points, std::span<const double> arc, std::size_t i,
                        const Vec2& p, double s_lo, double s_hi, PathProjection* best) {
  const double s0 = arc[i];
  const double len = arc[i + 1] - s0;
  if (len < kTinyLength) return;
  const Vec2& a = points[i];
  const Vec2 ab = points[i + 1] - a;
  const double t = std::clamp((p - a).dot(ab) / (len * len), 0.0, 1.0);
  const double s = std::clamp(s0 + t * len, s_lo, s_hi);
  const Vec2 q = a + ((s - s0) / len) * ab;
  const double d = (p - q).norm();
  if (d < best->distance) {  // strict: ties keep the earlier point
    best->distance = d;
    best->s = s;
    best->segment = i;
  }
}

SegmentRange SegmentsInWindow(std::span<const double> arc, double s_lo, double s_hi) {
  const std::size_t n = arc.size();
  if (n < 2) return {};
  // From the last point at or before s_lo (the first one if none) while a segment starts by s_hi.
  const auto after = std::upper_bound(arc.begin(), arc.end(), s_lo);
  const std::size_t first =
      after == arc.begin() ? 0 : static_cast<std::size_t>(after - arc.begin()) - 1;
  const auto beyond = std::upper_bound(arc.begin(), arc.end() - 1, s_hi);
  const std::size_t last = std::max(first, static_cast<std::size_t>(beyond - arc.begin()));
  return {first, last};
}

PathProjection ProjectOntoPath(std::span<const Vec2> points, std::span<const double> arc,
                               const Vec2& p, double s_lo, double s_hi) {
  RETRACE_CHECK(points.size() == arc.size());
  PathProjection best;
  best.s = s_lo;
  const SegmentRange range = SegmentsInWindow(arc, s_lo, s_hi);
  for (std::size_t i = range.first; i < range.last; ++i) {
    ProjectOntoSegment(points, arc, i, p, s_lo, s_hi, &best);
  }
  return best;
}

double ForwardProgress::Advance(std::span<const Vec2> points, std::span<const double> arc,
                                const Vec2& p, double s_hi) {
  const PathProjection proj = ProjectOntoPath(points, arc, p, value_, std::max(value_, s_hi));
  value_ = std::max(value_, proj.s);
  return value_;
}

void ForwardProgress::MoveTo(double s) { value_ = std::max(value_, s); }

}  // namespace retrace::core
