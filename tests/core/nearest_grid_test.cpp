#include "core/nearest_grid.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "core/rng.hpp"

namespace retrace::core {
namespace {

TEST(NearestGrid, PolylineDistanceMeasuresToTheSegmentsNotTheVertices) {
  // Vertices 2 m apart along x: midway between two of them, 0.5 m off the line, the polyline
  // is 0.5 m away and the nearest vertex sqrt(1 + 0.25) m.
  const PolylineDistance d({Vec2(0, 0), Vec2(2, 0), Vec2(4, 0), Vec2(4, 4)});
  EXPECT_DOUBLE_EQ(d(Vec2(1.0, 0.5)), 0.5);
  EXPECT_DOUBLE_EQ(d(Vec2(5.0, 2.0)), 1.0);   // beside the last segment
  EXPECT_DOUBLE_EQ(d(Vec2(-3.0, 4.0)), 5.0);  // before the first vertex
  EXPECT_EQ(PolylineDistance({})(Vec2(1, 1)), std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(PolylineDistance({Vec2(1, 1)})(Vec2(4, 5)), 5.0);  // one point
}

TEST(NearestGrid, MatchesABruteForceSearchAnywhere) {
  // A random walk of 2000 points over about 100 m, queried inside and far outside its extent.
  Rng rng(7);
  std::vector<Vec2> points{Vec2(0, 0)};
  for (int i = 0; i < 2000; ++i)
    points.push_back(points.back() + Vec2(rng.Normal(), rng.Normal()) * 0.8);
  const PolylineDistance d(points);
  for (int q = 0; q < 500; ++q) {
    const Vec2 p(rng.Uniform() * 400.0 - 200.0, rng.Uniform() * 400.0 - 200.0);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i + 1 < points.size(); ++i)
      best = std::min(best, SegmentDistance(p, points[i], points[i + 1]));
    ASSERT_DOUBLE_EQ(d(p), best) << p.transpose();
  }
}

}  // namespace
}  // namespace retrace::core
