#include "core/nearest_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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

// Within a distance and a range of items, with fine cells (as the revisit search along a long
// route uses it): the nearest item of the range nearer than the distance, lowest index on ties,
// as a brute-force search finds it.
TEST(NearestGrid, WithinADistanceAndARangeOfItemsMatchesABruteForceSearch) {
  Rng rng(11);
  std::vector<Vec2> a{Vec2(0, 0)}, b;
  for (int i = 0; i < 1500; ++i) {
    b.push_back(a.back() + Vec2(rng.Normal(), rng.Normal()) * 0.8);
    if (i + 1 < 1500) a.push_back(b.back());
  }
  const NearestGrid grid(a, b, 2.0);
  int found = 0;
  for (int q = 0; q < 2000; ++q) {
    // Near a random point of the walk, or anywhere around it.
    const Vec2 p = q % 2 == 0 ? a[static_cast<std::size_t>(rng.Uniform() * 1500.0)] +
                                    Vec2(rng.Normal(), rng.Normal()) * 2.0
                              : Vec2(rng.Uniform() * 120.0 - 60.0, rng.Uniform() * 120.0 - 60.0);
    const double max_distance = rng.Uniform() * 4.0;
    const auto first = static_cast<std::size_t>(rng.Uniform() * 1500.0);
    const std::size_t last =
        std::min<std::size_t>(first + 1 + static_cast<std::size_t>(rng.Uniform() * 800.0), 1500);
    const auto dist2 = [&](std::size_t i) { return SegmentDistanceSquared(p, a[i], b[i]); };
    std::size_t expected = NearestGrid::kNone;
    double best = max_distance * max_distance;
    for (std::size_t i = first; i < last; ++i) {
      if (dist2(i) < best) {
        best = dist2(i);
        expected = i;
      }
    }
    ASSERT_EQ(grid.Nearest(p, dist2, max_distance, first, last), expected)
        << p.transpose() << " within " << max_distance << " in [" << first << ", " << last << ")";
    found += expected != NearestGrid::kNone ? 1 : 0;
  }
  EXPECT_GT(found, 200);  // the test looked at both outcomes
  EXPECT_LT(found, 1800);
  // An empty range or no items: none.
  EXPECT_EQ(grid.Nearest(
                Vec2(0, 0), [](std::size_t) { return 0.0; }, 1.0, 5, 5),
            NearestGrid::kNone);
  EXPECT_EQ(NearestGrid().Nearest(Vec2(0, 0), [](std::size_t) { return 0.0; }), NearestGrid::kNone);
}

}  // namespace
}  // namespace retrace::core
