#pragma once
// Small synthetic inputs for the viz tests and helpers to look at rendered pixels.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <tuple>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "viz/figure_data.hpp"
#include "viz/figures.hpp"
#include "viz/image.hpp"

namespace retrace::viz::testing {

/// Straight segments between waypoints, one pose every `step` m, heading along the segment.
inline std::vector<core::Pose2> Densify(const std::vector<Vec2>& waypoints, double step) {
  std::vector<core::Pose2> out;
  for (std::size_t i = 0; i + 1 < waypoints.size(); ++i) {
    const Vec2 d = waypoints[i + 1] - waypoints[i];
    const double len = d.norm();
    const double th = std::atan2(d.y(), d.x());
    for (double s = 0.0; s < len; s += step) {
      const Vec2 p = waypoints[i] + d * (s / len);
      out.emplace_back(p.x(), p.y(), th);
    }
  }
  out.emplace_back(waypoints.back().x(), waypoints.back().y(), out.empty() ? 0.0 : out.back().theta);
  return out;
}

/// A 40 x 30 m world: one building (10..20, 10..18), an L-shaped one, a tree, an outer wall.
inline WorldShapes SmallWorld() {
  WorldShapes w;
  w.polygons.push_back({{10, 10}, {20, 10}, {20, 18}, {10, 18}});
  w.polygons.push_back({{25, 10}, {35, 10}, {35, 14}, {29, 14}, {29, 22}, {25, 22}});
  w.circles.push_back({Vec2(6, 20), 0.5});
  w.segments = {{Vec2(0, 0), Vec2(40, 0)}, {Vec2(40, 0), Vec2(40, 30)},
                {Vec2(40, 30), Vec2(0, 30)}, {Vec2(0, 30), Vec2(0, 0)}};
  return w;
}

/// The route around the first building: (3, 4) -> (37, 4) -> (37, 26) -> (3, 26).
inline std::vector<core::Pose2> SmallRoute() {
  return Densify({{3, 4}, {37, 4}, {37, 26}, {3, 26}}, 0.05);
}

/// A 20 x 14 m map at 0.1 m: free everywhere observed (x < 15 m), a wall of occupied cells
/// along y = 8 m, unknown beyond x = 15 m. Origin (-2, -4) so that M's origin is inside.
inline core::OccupancyGrid SmallGrid() {
  core::OccupancyGrid g(200, 140, 0.1, Vec2(-2.0, -4.0));
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < 170; ++x) g.SetLogOdds({x, y}, -3.0f);
  }
  const int wall_y = g.WorldToCell(Vec2(0.0, 8.05)).y;
  for (int x = 0; x < 170; ++x) g.SetLogOdds({x, wall_y}, 3.0f);
  return g;
}

/// The colour of the figure pixel holding panel point p.
inline Rgba PixelAt(const Image& img, const PanelInfo& panel, const Vec2& p) {
  const Vec2 q = panel.ToFigurePixel(p);
  return img.At(static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y())));
}

/// Whether two colours differ by at most `tol` per channel.
inline bool Near(Rgba a, Rgba b, int tol = 40) {
  return std::abs(a.r - b.r) <= tol && std::abs(a.g - b.g) <= tol && std::abs(a.b - b.b) <= tol;
}

inline ::testing::AssertionResult ColorNear(Rgba actual, Rgba expected, int tol = 40) {
  if (Near(actual, expected, tol)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "pixel (" << int(actual.r) << ", " << int(actual.g) << ", " << int(actual.b)
         << ") is not within " << tol << " of (" << int(expected.r) << ", " << int(expected.g)
         << ", " << int(expected.b) << ")";
}

/// Number of distinct colours (a blank image has one).
inline std::size_t DistinctColors(const Image& img) {
  std::set<std::tuple<int, int, int>> colors;
  for (std::size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
    colors.emplace(img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]);
    if (colors.size() > 1000) break;
  }
  return colors.size();
}

}  // namespace retrace::viz::testing
