#include "viz/internal/polyline.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/segment.hpp"

namespace retrace::viz::internal {

std::vector<core::Vec2> SimplifyPolyline(const std::vector<core::Vec2>& points, double tolerance) {
  // Radial pass: consecutive points closer than the tolerance to the last kept one go.
  std::vector<core::Vec2> radial;
  radial.reserve(points.size());
  for (const core::Vec2& p : points) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) continue;
    if (radial.empty() || (p - radial.back()).norm() > tolerance) radial.push_back(p);
  }
  if (!points.empty() && radial.size() >= 1) {
    // Keep the true last point so that a path ends where it ends.
    const core::Vec2& last = points.back();
    if (std::isfinite(last.x()) && std::isfinite(last.y()) && radial.back() != last) {
      if (radial.size() >= 2 && (last - radial.back()).norm() <= tolerance) radial.back() = last;
      else radial.push_back(last);
    }
  }
  if (radial.size() <= 2) return radial;

  // Douglas-Peucker with an explicit stack (no recursion depth limit on long paths).
  std::vector<char> keep(radial.size(), 0);
  keep.front() = 1;
  keep.back() = 1;
  std::vector<std::pair<std::size_t, std::size_t>> stack{{0, radial.size() - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    double worst = -1.0;
    std::size_t worst_k = i;
    for (std::size_t k = i + 1; k < j; ++k) {
      const double d = core::SegmentDistance(radial[k], radial[i], radial[j]);
      if (d > worst) {
        worst = d;
        worst_k = k;
      }
    }
    if (worst > tolerance) {
      keep[worst_k] = 1;
      stack.emplace_back(i, worst_k);
      stack.emplace_back(worst_k, j);
    }
  }
  std::vector<core::Vec2> out;
  for (std::size_t k = 0; k < radial.size(); ++k) {
    if (keep[k] != 0) out.push_back(radial[k]);
  }
  return out;
}

}  // namespace retrace::viz::internal
