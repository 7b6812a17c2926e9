// The grid over a path's segments (core/path_index.hpp) answers as ProjectOntoPath does for every
// point within its radius, and with nothing beyond it.

#include "core/path_index.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/rng.hpp"

namespace retrace::core {
namespace {

// A random walk that turns often and crosses itself, with long and very short segments and a
// repeated point (a zero-length segment).
std::vector<Vec2> TangledPath(Rng& rng, std::size_t n) {
  std::vector<Vec2> path{{0, 0}};
  double heading = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    heading += rng.Uniform(-2.0, 2.0);
    const double step =
        i % 17 == 0 ? 0.0 : (i % 5 == 0 ? rng.Uniform(5.0, 30.0) : rng.Uniform(0.01, 2.0));
    path.push_back(path.back() + step * Vec2(std::cos(heading), std::sin(heading)));
  }
  return path;
}

TEST(PathIndex, AnswersAsProjectOntoPathWithinItsRadius) {
  Rng rng(7);
  for (const double radius : {0.3, 3.0, 20.0}) {
    const std::vector<Vec2> path = TangledPath(rng, 400);
    const std::vector<double> arc = CumulativeArcLength(path);
    const PathIndex index(path, arc, radius);
    int within = 0, beyond = 0;
    for (int q = 0; q < 4000; ++q) {
      const Vec2 p = path[static_cast<std::size_t>(rng.Uniform(0.0, 400.0))] +
                     Vec2(rng.Uniform(-2.0, 2.0) * radius, rng.Uniform(-2.0, 2.0) * radius);
      double lo = rng.Uniform(-5.0, arc.back() + 5.0);
      double hi = rng.Uniform(-5.0, arc.back() + 5.0);
      if (q % 3 != 0 && lo > hi) std::swap(lo, hi);  // a third keep an empty window
      const PathProjection want = ProjectOntoPath(path, arc, p, lo, hi);
      const PathProjection got = index.Project(p, lo, hi);
      if (want.distance < radius) {
        ++within;
        EXPECT_EQ(got.distance, want.distance) << "radius " << radius << ", query " << q;
        EXPECT_EQ(got.s, want.s);
        EXPECT_EQ(got.segment, want.segment);
      } else {
        ++beyond;
        EXPECT_EQ(got.distance, std::numeric_limits<double>::infinity());
        EXPECT_EQ(got.s, lo);
      }
    }
    EXPECT_GT(within, 500) << "too few queries within the radius to test it";
    EXPECT_GT(beyond, 500) << "too few queries beyond the radius to test it";
  }
}

TEST(PathIndex, WidensItsCellsForALongPathAndStillFindsItsPoints) {
  // 200 km of back-and-forth lines 1 m apart: more than 2^20 cells of the 0.1 m radius.
  std::vector<Vec2> path;
  for (int k = 0; k < 20000; ++k) {
    path.emplace_back(k % 2 == 0 ? 0.0 : 10'000.0, static_cast<double>(k / 2));
    path.emplace_back(k % 2 == 0 ? 10'000.0 : 0.0, static_cast<double>(k / 2));
  }
  // (the doubled turn points are zero-length segments)
  const std::vector<double> arc = CumulativeArcLength(path);
  const PathIndex index(path, arc, 0.1);
  EXPECT_GT(index.cell_size(), 0.1);
  const Vec2 p(4321.0, 3.05);  // 0.05 m from the lines at y = 3, passed twice
  const PathProjection got = index.Project(p, 0.0, arc.back());
  const PathProjection want = ProjectOntoPath(path, arc, p, 0.0, arc.back());
  EXPECT_NEAR(got.distance, 0.05, 1e-9);
  EXPECT_EQ(got.s, want.s);
  EXPECT_EQ(index.Project(Vec2(4321.0, 3.5), 0.0, arc.back()).distance,
            std::numeric_limits<double>::infinity());
}

TEST(PathIndex, IsEmptyForFewerThanTwoPoints) {
  const std::vector<Vec2> one{{1, 1}};
  const std::vector<double> arc = CumulativeArcLength(one);
  const PathIndex index(one, arc, 1.0);
  EXPECT_EQ(index.Project({1, 1}, 0.0, 1.0).distance, std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace retrace::core
