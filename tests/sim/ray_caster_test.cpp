#include "sim/ray_caster.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/angle.hpp"
#include "core/rng.hpp"
#include "tests/support/special_values.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::kInf;

Vec2 Dir(double angle) { return {std::cos(angle), std::sin(angle)}; }

std::vector<Vec2> CornerBox(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// Closest hit over every primitive: the definition the grid must reproduce bit for bit.
double BruteForceCast(const StaticGeometry& g, const Vec2& o, const Vec2& d, double max_t) {
  double best = kInf;
  for (const Segment& s : g.segments()) best = std::min(best, RaySegmentHit(o, d, s));
  for (const Circle& c : g.circles()) best = std::min(best, RayCircleHit(o, d, c));
  return best <= max_t ? best : kInf;
}

TEST(RayCaster, HitsBoxWallsAtAnalyticDistances) {
  StaticGeometry g;
  g.AddPolygon(CornerBox(-2.0, -1.0, 3.0, 4.0));
  const RayCaster caster(g);
  const Vec2 o(0.0, 0.0);
  EXPECT_EQ(caster.Cast(o, Dir(0.0), 100.0), 3.0);
  EXPECT_EQ(caster.Cast(o, {-1.0, 0.0}, 100.0), 2.0);
  EXPECT_EQ(caster.Cast(o, {0.0, 1.0}, 100.0), 4.0);
  EXPECT_EQ(caster.Cast(o, {0.0, -1.0}, 100.0), 1.0);
  // Oblique beams: the right wall x = 3 for |angle| < atan(4/3), the top wall beyond it.
  for (const double a : {0.1, 0.5, 0.9, -0.3, -0.3217}) {
    EXPECT_NEAR(caster.Cast(o, Dir(a), 100.0), 3.0 / std::cos(a), 1e-12) << a;
  }
  for (const double a : {1.0, 1.3, 1.8, 2.0}) {
    EXPECT_NEAR(caster.Cast(o, Dir(a), 100.0), 4.0 / std::sin(a), 1e-12) << a;
  }
  EXPECT_NEAR(caster.Cast(o, Dir(-2.0), 100.0), 1.0 / std::sin(2.0), 1e-12);
}

TEST(RayCaster, HitsSegmentsFromBothSides) {
  StaticGeometry g;
  g.AddEdges({{{2.0, -1.0}, {2.0, 1.0}}}, {});
  const RayCaster caster(g);
  EXPECT_EQ(caster.Cast({0.0, 0.0}, {1.0, 0.0}, 10.0), 2.0);
  EXPECT_EQ(caster.Cast({4.0, 0.0}, {-1.0, 0.0}, 10.0), 2.0);
  EXPECT_EQ(caster.Cast({0.0, 0.0}, {-1.0, 0.0}, 10.0), kInf);
  // Through the end point counts; just past it does not.
  EXPECT_EQ(caster.Cast({0.0, 1.0}, {1.0, 0.0}, 10.0), 2.0);
  EXPECT_EQ(caster.Cast({0.0, 1.001}, {1.0, 0.0}, 10.0), kInf);
  EXPECT_NEAR(caster.Cast({0.0, 0.0}, Vec2(2.0, 0.9).normalized(), 10.0), std::hypot(2.0, 0.9),
              1e-12);
}

TEST(RayCaster, HitsCircleAtAnalyticDistanceFromOutsideAndInside) {
  StaticGeometry g;
  g.AddCircle({{5.0, 0.0}, 1.0});
  const RayCaster caster(g);
  EXPECT_EQ(caster.Cast({0.0, 0.0}, {1.0, 0.0}, 10.0), 4.0);
  for (const double a : {0.05, 0.1, -0.15, 0.2}) {
    const double expected = 5.0 * std::cos(a) - std::sqrt(1.0 - 25.0 * std::sin(a) * std::sin(a));
    EXPECT_NEAR(caster.Cast({0.0, 0.0}, Dir(a), 10.0), expected, 1e-12) << a;
  }
  EXPECT_EQ(caster.Cast({0.0, 0.0}, Dir(0.21), 10.0), kInf);  // asin(1/5) = 0.2014
  EXPECT_EQ(caster.Cast({0.0, 0.0}, {-1.0, 0.0}, 10.0), kInf);
  // From inside, the boundary is met on the way out.
  EXPECT_EQ(caster.Cast({5.0, 0.5}, {0.0, 1.0}, 10.0), 0.5);
  EXPECT_EQ(caster.Cast({5.0, 0.5}, {0.0, -1.0}, 10.0), 1.5);
}

TEST(RayCaster, HitsRegularPolygonFromItsCentre) {
  // Hexagon with circumradius 2 centred at (10, -3), rotated by 0.2 rad; apothem = 2 cos(pi/6).
  const Vec2 centre(10.0, -3.0);
  const double rot = 0.2;
  std::vector<Vec2> ring;
  for (int k = 0; k < 6; ++k) ring.push_back(centre + 2.0 * Dir(rot + k * core::kPi / 3.0));
  StaticGeometry g;
  g.AddPolygon(ring);
  const RayCaster caster(g);
  const double apothem = 2.0 * std::cos(core::kPi / 6.0);
  for (int i = 0; i < 37; ++i) {
    const double a = -core::kPi + i * 0.17;
    // The face whose outward normal is nearest to the beam (normals at rot + pi/6 + k pi/3).
    double off = std::remainder(a - (rot + core::kPi / 6.0), core::kPi / 3.0);
    EXPECT_NEAR(caster.Cast(centre, Dir(a), 100.0), apothem / std::cos(off), 1e-12) << a;
  }
  // And from outside: the face towards the origin, along the line through the centre.
  const double d = (centre - Vec2(0.0, 0.0)).norm();
  const Vec2 to_centre = centre / d;
  const double a_in = std::atan2(-to_centre.y(), -to_centre.x());
  const double off = std::remainder(a_in - (rot + core::kPi / 6.0), core::kPi / 3.0);
  EXPECT_NEAR(caster.Cast({0.0, 0.0}, to_centre, 100.0), d - apothem / std::cos(off), 1e-12);
}

TEST(RayCaster, ReturnsInfinityWithoutHitWithinMaxRange) {
  StaticGeometry g;
  g.AddPolygon(CornerBox(10.0, -1.0, 11.0, 1.0));
  const RayCaster caster(g);
  EXPECT_EQ(caster.Cast({0.0, 0.0}, {0.0, 1.0}, 100.0), kInf);  // open space
  EXPECT_EQ(caster.Cast({0.0, 0.0}, {1.0, 0.0}, 9.5), kInf);    // beyond max range
  EXPECT_EQ(caster.Cast({0.0, 0.0}, {1.0, 0.0}, 10.0), 10.0);   // exactly at max range
  EXPECT_EQ(caster.Cast({0.0, 0.0}, {1.0, 0.0}, kInf), 10.0);
  EXPECT_EQ(caster.Cast({0.0, 0.0}, {1.0, 0.0}, 0.0), kInf);
  EXPECT_EQ(caster.Cast({0.0, 0.0}, {1.0, 0.0}, -1.0), kInf);

  const RayCaster empty{StaticGeometry{}};
  EXPECT_EQ(empty.Cast({0.0, 0.0}, {1.0, 0.0}, kInf), kInf);
}

TEST(RayCaster, ScalesHitParameterWithDirectionLength) {
  StaticGeometry g;
  g.AddPolygon(CornerBox(-1.0, -1.0, 4.0, 1.0));
  g.AddCircle({{-6.0, 0.0}, 1.0});
  const RayCaster caster(g);
  EXPECT_EQ(caster.Cast({0.0, 0.0}, {2.0, 0.0}, 10.0), 2.0);
  EXPECT_EQ(caster.Cast({-3.0, 0.0}, {-0.5, 0.0}, 10.0), 4.0);
}

TEST(RayCaster, FindsGeometryFromOriginsOutsideItsBounds) {
  StaticGeometry g;
  g.AddPolygon(CornerBox(0.0, 0.0, 1.0, 1.0));
  const RayCaster caster(g);
  EXPECT_EQ(caster.Cast({-100.0, 0.5}, {1.0, 0.0}, kInf), 100.0);
  EXPECT_NEAR(caster.Cast({-5.0, -5.0}, Vec2(1.0, 1.0).normalized(), kInf), 5.0 * std::sqrt(2.0),
              1e-12);
  EXPECT_EQ(caster.Cast({-100.0, 5.0}, {1.0, 0.0}, kInf), kInf);
}

// A random world of boxes, rotated polygons, loose segments and circles.
StaticGeometry RandomWorld(std::uint64_t seed) {
  core::Rng rng(seed);
  StaticGeometry g;
  for (int i = 0; i < 60; ++i) {
    const double x = rng.Uniform(0.0, 50.0), y = rng.Uniform(0.0, 50.0);
    g.AddPolygon(CornerBox(x, y, x + rng.Uniform(0.1, 6.0), y + rng.Uniform(0.1, 6.0)));
  }
  for (int i = 0; i < 40; ++i) {
    const Vec2 c(rng.Uniform(0.0, 50.0), rng.Uniform(0.0, 50.0));
    const int k = 3 + static_cast<int>(rng.UniformIndex(6));
    const double r = rng.Uniform(0.2, 3.0), rot = rng.Uniform(-3.0, 3.0);
    std::vector<Vec2> ring;
    for (int j = 0; j < k; ++j) ring.push_back(c + r * Dir(rot + 2.0 * core::kPi * j / k));
    g.AddPolygon(ring);
  }
  std::vector<Segment> loose;
  for (int i = 0; i < 150; ++i) {
    const Vec2 a(rng.Uniform(0.0, 50.0), rng.Uniform(0.0, 50.0));
    loose.push_back({a, a + rng.Uniform(0.0, 15.0) * Dir(rng.Uniform(-3.2, 3.2))});
  }
  g.AddEdges(loose, {});
  for (int i = 0; i < 40; ++i) {
    g.AddCircle({{rng.Uniform(0.0, 50.0), rng.Uniform(0.0, 50.0)}, rng.Uniform(0.05, 2.0)});
  }
  return g;
}

TEST(RayCaster, AgreesBitForBitWithBruteForceOnRandomRays) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const StaticGeometry g = RandomWorld(seed);
    for (const double cell : {0.0, 0.13, 1.0, 7.3}) {
      const RayCaster caster(g, cell);
      core::Rng rng(seed * 100 + 7);
      int hits = 0;
      for (int i = 0; i < 4000; ++i) {
        const Vec2 o(rng.Uniform(-10.0, 60.0), rng.Uniform(-10.0, 60.0));
        const Vec2 d = Dir(rng.Uniform(-core::kPi, core::kPi));
        const double max_t = i % 4 == 0 ? kInf : rng.Uniform(0.0, 40.0);
        const double expected = BruteForceCast(g, o, d, max_t);
        ASSERT_EQ(caster.Cast(o, d, max_t), expected)
            << "seed " << seed << " cell " << cell << " ray " << i;
        hits += std::isfinite(expected) ? 1 : 0;
      }
      EXPECT_GT(hits, 2000);  // the comparison is not vacuous
    }
  }
}

TEST(RayCaster, AgreesWithBruteForceOnGridAlignedWallsAndCornerRays) {
  // Walls on the cell boundaries of a 1 m grid and rays through cell corners: the cases where
  // a walk that is not conservative misses a wall.
  StaticGeometry g;
  std::vector<Segment> edges;
  for (int k = 0; k <= 10; ++k) {
    for (int j = 0; j < 10; j += 2) {
      edges.push_back({{static_cast<double>(k), static_cast<double>(j)},
                       {static_cast<double>(k), static_cast<double>(j + 1)}});
      edges.push_back({{static_cast<double>(j + 1), static_cast<double>(k)},
                       {static_cast<double>(j + 2), static_cast<double>(k)}});
    }
  }
  g.AddEdges(edges, {});
  g.AddCircle({{5.0, 5.0}, 0.5});
  for (const double cell : {0.0, 0.5, 1.0}) {
    const RayCaster caster(g, cell);
    for (int x = -1; x <= 11; ++x) {
      for (int y = -1; y <= 11; ++y) {
        for (int a = 0; a < 16; ++a) {
          const Vec2 o(x, y);
          const Vec2 d = Dir(a * core::kPi / 8.0);
          EXPECT_EQ(caster.Cast(o, d, 30.0), BruteForceCast(g, o, d, 30.0))
              << "cell " << cell << " origin " << x << "," << y << " dir " << a;
        }
      }
    }
  }
}

TEST(RayCaster, CastFanMatchesSingleCasts) {
  const StaticGeometry g = RandomWorld(9);
  const RayCaster caster(g);
  std::vector<Vec2> dirs;
  std::vector<double> max_t;
  for (int i = 0; i < 360; ++i) {
    dirs.push_back(Dir(i * core::kPi / 180.0));
    max_t.push_back(i % 3 == 0 ? 5.0 : 30.0);
  }
  const Vec2 o(25.0, 25.0);
  std::vector<double> out(dirs.size());
  caster.CastFan(o, dirs, max_t, out);
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    EXPECT_EQ(out[i], caster.Cast(o, dirs[i], max_t[i])) << i;
  }
  // In place.
  caster.CastFan(o, dirs, max_t, max_t);
  EXPECT_EQ(max_t, out);
}

// A scanner's beams as the Lidar makes them: unit vectors at first + i * step rotated by theta.
std::vector<Vec2> ScanDirections(double theta, double first, double step, int n) {
  std::vector<Vec2> dirs;
  const double c = std::cos(theta), s = std::sin(theta);
  for (int i = 0; i < n; ++i) {
    const Vec2 d = Dir(first + i * step);
    dirs.emplace_back(c * d.x() - s * d.y(), s * d.x() + c * d.y());
  }
  return dirs;
}

// Wedges (runs of beams cast together) give every beam the single cast's range bit for bit: on
// random worlds, for grid cells from much finer than the beams' spacing to far coarser, whole
// turns and narrow fans, coarse and fine steps, with short, long, infinite, zero and negative
// ray limits, and origins anywhere inside.
TEST(RayCaster, FanWedgesAgreeBitForBitWithSingleCasts) {
  std::size_t in_wedges = 0, rays = 0;
  int hits = 0;
  for (const std::uint64_t seed : {4u, 5u}) {
    const StaticGeometry g = RandomWorld(seed);
    for (const double cell : {0.0, 0.13, 1.0, 7.3, 25.0}) {
      const RayCaster caster(g, cell);
      core::Rng rng(seed * 31 + 1);
      for (int fan = 0; fan < 60; ++fan) {
        const int n = 2 + static_cast<int>(rng.UniformIndex(1100));
        const double fov = fan % 3 == 0 ? 2.0 * core::kPi : rng.Uniform(0.01, 2.0 * core::kPi);
        const std::vector<Vec2> dirs =
            ScanDirections(rng.Uniform(-core::kPi, core::kPi), -0.5 * fov, fov / n, n);
        std::vector<double> max_t;
        for (int i = 0; i < n; ++i) {
          const double u = rng.Uniform();
          max_t.push_back(u < 0.05  ? -1.0
                          : u < 0.1 ? 0.0
                          : u < 0.4 ? kInf
                                    : rng.Uniform(0.0, 60.0));
        }
        const Vec2 o(rng.Uniform(0.01, 49.9), rng.Uniform(0.01, 49.9));
        std::vector<double> out(dirs.size());
        in_wedges += caster.CastFan(o, dirs, max_t, out);
        rays += dirs.size();
        for (std::size_t i = 0; i < dirs.size(); ++i) {
          ASSERT_EQ(out[i], caster.Cast(o, dirs[i], max_t[i]))
              << "seed " << seed << " cell " << cell << " fan " << fan << " ray " << i;
          hits += std::isfinite(out[i]) ? 1 : 0;
        }
      }
    }
  }
  // Not vacuous: most rays went through wedges, and most of them hit something.
  EXPECT_GT(in_wedges, rays / 2);
  EXPECT_GT(hits, static_cast<int>(rays / 3));
}

// Fans from grid corners and cell sides through a grid of walls on the cell boundaries, with
// beams through wall ends: where a wedge whose edge walks were not conservative would lose a wall.
TEST(RayCaster, FanWedgesAgreeOnGridAlignedWalls) {
  StaticGeometry g;
  std::vector<Segment> edges;
  for (int k = 0; k <= 20; ++k) {
    for (int j = 0; j < 20; j += 3) {
      edges.push_back({{k * 1.0, j * 1.0}, {k * 1.0, j + 1.0}});
      edges.push_back({{j + 1.0, k * 1.0}, {j + 2.0, k * 1.0}});
    }
  }
  g.AddEdges(edges, {});
  for (const double cell : {1.0, 2.0, 4.0}) {
    const RayCaster caster(g, cell);
    std::size_t in_wedges = 0;
    for (const Vec2& o :
         {Vec2(10.0, 10.0), Vec2(10.5, 10.0), Vec2(9.999999, 10.5), Vec2(3.0, 17.0)}) {
      for (const int n : {8, 360, 1440}) {
        const std::vector<Vec2> dirs = ScanDirections(0.0, 0.0, 2.0 * core::kPi / n, n);
        const std::vector<double> max_t(dirs.size(), 40.0);
        std::vector<double> out(dirs.size());
        in_wedges += caster.CastFan(o, dirs, max_t, out);
        for (std::size_t i = 0; i < dirs.size(); ++i) {
          ASSERT_EQ(out[i], BruteForceCast(g, o, dirs[i], 40.0))
              << "cell " << cell << " origin " << o.transpose() << " n " << n << " ray " << i;
        }
      }
    }
    EXPECT_GT(in_wedges, 0u) << cell;
  }
}

}  // namespace
}  // namespace retrace::sim
