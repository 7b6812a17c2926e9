#include "nav/grid_ray_caster.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/angle.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"

namespace retrace::nav {
namespace {

using core::Vec2;

// A 20 m x 15 m grid at 0.1 m with a room outline (open on one side, so rays leave the map)
// and random blobs.
core::OccupancyGrid RandomMap(std::uint64_t seed) {
  core::OccupancyGrid g(200, 150, 0.1, Vec2(-3.3, -1.7));
  core::Rng rng(seed);
  for (int y = 0; y < 150; ++y) {
    for (int x = 0; x < 200; ++x) {
      const bool wall = (y == 10 || y == 140 || x == 10) && !(y > 60 && y < 80);
      g.SetProbability({x, y}, wall ? 0.95 : 0.05);
    }
  }
  for (int k = 0; k < 40; ++k) {
    const int cx = static_cast<int>(rng.UniformIndex(200)), cy = static_cast<int>(rng.UniformIndex(150));
    const int r = static_cast<int>(rng.UniformIndex(6));
    for (int y = cy - r; y <= cy + r; ++y) {
      for (int x = cx - r; x <= cx + r; ++x) {
        if (g.Contains({x, y}) && (x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) {
          g.SetProbability({x, y}, 0.95);
        }
      }
    }
  }
  return g;
}

TEST(GridRayCaster, SphereTracingIsBitIdenticalToDdaOnRandomRays) {
  int hits = 0, misses = 0, outside_starts = 0, total = 0;
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    const core::OccupancyGrid g = RandomMap(seed);
    const LikelihoodField f(g, {}, 30.0);
    const GridRayCaster caster(f);
    core::Rng rng(seed + 100);
    for (int i = 0; i < 2000; ++i) {
      // Starts anywhere in and around the map (some outside), some on exact cell boundaries,
      // some along the axes.
      double x = rng.Uniform(-6.0, 20.0), y = rng.Uniform(-4.0, 16.0);
      if (i % 7 == 0) x = -3.3 + 0.1 * static_cast<double>(rng.UniformIndex(200));
      double a = rng.Uniform(-core::kPi, core::kPi);
      if (i % 11 == 0) a = core::kPi / 2.0 * static_cast<double>(rng.UniformIndex(4)) - core::kPi;
      if (i % 13 == 0) a = core::kPi / 4.0;
      const double range_max = i % 5 == 0 ? rng.Uniform(0.0, 5.0) : 30.0;
      const double dx = std::cos(a), dy = std::sin(a);
      const double fast = caster.Cast(x, y, dx, dy, range_max);
      const double ref = caster.CastDda(x, y, dx, dy, range_max);
      ASSERT_EQ(std::bit_cast<std::uint64_t>(fast), std::bit_cast<std::uint64_t>(ref))
          << "seed " << seed << " ray " << i << " from (" << x << ", " << y << ") angle " << a;
      ++total;
      (std::isinf(ref) ? misses : hits) += 1;
      outside_starts += g.Contains(g.WorldToCell(Vec2(x, y))) ? 0 : 1;
      if (!std::isinf(ref)) {
        EXPECT_LE(ref, range_max);
      }
    }
  }
  std::printf("[ report ] %d rays: %d hits, %d no-hit, %d starting outside the map; all identical\n",
              total, hits, misses, outside_starts);
  EXPECT_GT(hits, 1000);
  EXPECT_GT(misses, 500);
  EXPECT_GT(outside_starts, 1000);
}

TEST(GridRayCaster, CastManyIsBitIdenticalToDdaOnRandomBundles) {
  // Bundles like the localizer's: rays of one beam from particles scattered around a pose, plus
  // rays starting outside the map, axis-aligned rays and short range limits.
  int total = 0, hits = 0;
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    const core::OccupancyGrid g = RandomMap(seed);
    const LikelihoodField f(g, {}, 30.0);
    const GridRayCaster caster(f);
    core::Rng rng(seed + 200);
    for (int bundle = 0; bundle < 40; ++bundle) {
      const std::size_t n = rng.UniformIndex(60);  // includes empty bundles
      const double cx = rng.Uniform(-6.0, 20.0), cy = rng.Uniform(-4.0, 16.0);
      const double a = rng.Uniform(-core::kPi, core::kPi);
      const double spread = bundle % 3 == 0 ? 3.0 : 0.1;
      const double range_max = bundle % 5 == 0 ? rng.Uniform(0.0, 5.0) : 30.0;
      std::vector<double> x(n), y(n), dx(n), dy(n), out(n);
      for (std::size_t i = 0; i < n; ++i) {
        x[i] = cx + spread * rng.Normal();
        y[i] = cy + spread * rng.Normal();
        double ai = a + 0.05 * spread * rng.Normal();
        if (i % 11 == 0) ai = core::kPi / 2.0 * static_cast<double>(rng.UniformIndex(4)) - core::kPi;
        dx[i] = std::cos(ai);
        dy[i] = std::sin(ai);
      }
      caster.CastMany(x, y, dx, dy, range_max, out);
      for (std::size_t i = 0; i < n; ++i) {
        const double ref = caster.CastDda(x[i], y[i], dx[i], dy[i], range_max);
        ASSERT_EQ(std::bit_cast<std::uint64_t>(out[i]), std::bit_cast<std::uint64_t>(ref))
            << "seed " << seed << " bundle " << bundle << " ray " << i;
        ++total;
        hits += std::isinf(ref) ? 0 : 1;
      }
    }
  }
  std::printf("[ report ] %d bundled rays, %d hits; all identical\n", total, hits);
  EXPECT_GT(total, 4000);
  EXPECT_GT(hits, 1000);
}

TEST(GridRayCaster, GrazingRaysAlongWallsAreBitIdenticalToDda) {
  // Rays nearly parallel to a wall, at distances of a few cells and less: the sphere steps
  // shrink and the exact traversal does most of the work.
  const core::OccupancyGrid g = RandomMap(7);
  const LikelihoodField f(g, {}, 30.0);
  const GridRayCaster caster(f);
  core::Rng rng(9);
  std::vector<double> x, y, dx, dy;
  for (int i = 0; i < 3000; ++i) {
    // The wall row y = 10 spans y in [-0.7, -0.6); start just above it, heading along it.
    x.push_back(rng.Uniform(-3.0, 16.0));
    y.push_back(-0.6 + rng.Uniform(0.0, 0.5));
    const double a = (i % 2 == 0 ? 0.0 : core::kPi) + rng.Uniform(-0.1, 0.1);
    dx.push_back(std::cos(a));
    dy.push_back(std::sin(a));
  }
  std::vector<double> out(x.size());
  caster.CastMany(x, y, dx, dy, 30.0, out);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double ref = caster.CastDda(x[i], y[i], dx[i], dy[i], 30.0);
    ASSERT_EQ(std::bit_cast<std::uint64_t>(out[i]), std::bit_cast<std::uint64_t>(ref)) << "ray " << i;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(caster.Cast(x[i], y[i], dx[i], dy[i], 30.0)),
              std::bit_cast<std::uint64_t>(ref))
        << "ray " << i;
  }
}

TEST(GridRayCaster, CastManyIsBitIdenticalToDdaAtTheMapEdgesAndFromFarAway) {
  // CastMany indexes the clearance of a lane's position without clamping it to the map (a
  // padding row and column catch positions a hair past the far edges) and leaves rays from
  // farther than 2^20 cells to Cast. Rays entering across every edge, running along the edges
  // just inside them, and starting 10^6 km away must all agree with CastDda.
  const core::OccupancyGrid g = RandomMap(3);  // x in [-3.3, 16.7), y in [-1.7, 13.3)
  const LikelihoodField f(g, {}, 30.0);
  const GridRayCaster caster(f);
  const double x0 = -3.3, x1 = 16.7, y0 = -1.7, y1 = 13.3;
  core::Rng rng(21);
  std::vector<double> x, y, dx, dy;
  const auto add = [&](double px, double py, double a) {
    x.push_back(px);
    y.push_back(py);
    dx.push_back(std::cos(a));
    dy.push_back(std::sin(a));
  };
  for (int i = 0; i < 400; ++i) {
    const double u = rng.Uniform(0.0, 1.0), a = rng.Uniform(-core::kPi, core::kPi);
    // On each edge, exactly and a hair inside or outside it.
    const double eps = (i % 3 - 1) * 1e-9;
    add(x0 + eps, y0 + u * (y1 - y0), a);
    add(x1 + eps, y0 + u * (y1 - y0), a);
    add(x0 + u * (x1 - x0), y0 + eps, a);
    add(x0 + u * (x1 - x0), y1 + eps, a);
    // Along the far edges, just inside, nearly parallel to them.
    const double along = rng.Uniform(-1e-3, 1e-3);
    add(x0 + u * (x1 - x0), y1 - 1e-7, (i % 2 == 0 ? 0.0 : core::kPi) + along);
    add(x1 - 1e-7, y0 + u * (y1 - y0), (i % 2 == 0 ? 0.5 : -0.5) * core::kPi + along);
    // From far outside, aimed at the map (and some missing it).
    const double far = i % 2 == 0 ? 1e9 : 5.0e4;
    const double tx = x0 + u * (x1 - x0), ty = y0 + rng.Uniform(-2.0, 17.0);
    add(tx - far * std::cos(a), ty - far * std::sin(a), a);
  }
  int hits = 0;
  for (const double range_max : {30.0, 2e9}) {
    std::vector<double> out(x.size());
    caster.CastMany(x, y, dx, dy, range_max, out);
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double ref = caster.CastDda(x[i], y[i], dx[i], dy[i], range_max);
      ASSERT_EQ(std::bit_cast<std::uint64_t>(out[i]), std::bit_cast<std::uint64_t>(ref))
          << "ray " << i << " from (" << x[i] << ", " << y[i] << ") range_max " << range_max;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(caster.Cast(x[i], y[i], dx[i], dy[i], range_max)),
                std::bit_cast<std::uint64_t>(ref))
          << "ray " << i;
      hits += std::isinf(ref) ? 0 : 1;
    }
  }
  EXPECT_GT(hits, 1000);
}

// A 120 m x 120 m map at 0.1 m with thin walls at random angles and round trees, large enough
// that rays of 30 m from its middle never reach its edges.
core::OccupancyGrid LargeMap(std::uint64_t seed) {
  constexpr int kCells = 1200;
  core::OccupancyGrid g(kCells, kCells, 0.1, Vec2(-60.0, -60.0));
  std::vector<float>& l = g.log_odds();
  std::fill(l.begin(), l.end(), static_cast<float>(core::Logit(0.05)));
  const auto set = [&](int x, int y) {
    if (x >= 0 && y >= 0 && x < kCells && y < kCells) {
      l[static_cast<std::size_t>(y) * kCells + static_cast<std::size_t>(x)] =
          static_cast<float>(core::Logit(0.95));
    }
  };
  core::Rng rng(seed);
  for (int k = 0; k < 60; ++k) {  // walls, 1-2 cells thick, 5-40 m long
    const double x = rng.Uniform(0, kCells), y = rng.Uniform(0, kCells);
    const double a = rng.Uniform(-core::kPi, core::kPi), len = rng.Uniform(50, 400);
    const int thick = 1 + static_cast<int>(rng.UniformIndex(2));
    for (double d = 0; d < len; d += 0.5) {
      for (int t = 0; t < thick; ++t) {
        set(static_cast<int>(x + d * std::cos(a)) + t, static_cast<int>(y + d * std::sin(a)));
      }
    }
  }
  for (int k = 0; k < 600; ++k) {  // trees, radius 0-4 cells
    const int cx = static_cast<int>(rng.UniformIndex(kCells));
    const int cy = static_cast<int>(rng.UniformIndex(kCells));
    const int r = static_cast<int>(rng.UniformIndex(5));
    for (int y = -r; y <= r; ++y) {
      for (int x = -r; x <= r; ++x) {
        if (x * x + y * y <= r * r) set(cx + x, cy + y);
      }
    }
  }
  return g;
}

TEST(GridRayCaster, CastManyIsBitIdenticalToDdaOnParticleCloudsInALargeMap) {
  // The localizer's bundles: the rays of one beam from 300 particles scattered around a pose
  // (0.1 m, 0.02 rad), in the order of their headings, so that CastMany clears a common start
  // for each group of rays. Clouds in the middle of the map (rays that cannot leave it), near
  // and across its edges, and short range limits (a group clear beyond its end).
  int total = 0, hits = 0;
  for (std::uint64_t seed = 0; seed < 2; ++seed) {
    const core::OccupancyGrid g = LargeMap(seed);
    const LikelihoodField f(g, {}, 30.0);
    const GridRayCaster caster(f);
    core::Rng rng(seed + 300);
    for (int cloud = 0; cloud < 12; ++cloud) {
      const bool middle = cloud % 3 != 2;
      const double cx = middle ? rng.Uniform(-25.0, 25.0) : rng.Uniform(-62.0, 62.0);
      const double cy = middle ? rng.Uniform(-25.0, 25.0) : rng.Uniform(-62.0, 62.0);
      const double theta = rng.Uniform(-core::kPi, core::kPi);
      const double range_max = cloud % 4 == 3 ? rng.Uniform(0.5, 4.0) : 30.0;
      std::vector<core::Pose2> particles;
      for (int j = 0; j < 300; ++j) {
        particles.emplace_back(cx + 0.1 * rng.Normal(), cy + 0.1 * rng.Normal(),
                               theta + 0.02 * rng.Normal());
      }
      std::sort(particles.begin(), particles.end(),
                [](const core::Pose2& a, const core::Pose2& b) { return a.theta < b.theta; });
      const std::size_t n = particles.size();
      for (int beam = 0; beam < 24; ++beam) {
        const double angle = -0.75 * core::kPi + beam * (1.5 * core::kPi / 23.0);
        std::vector<double> x(n), y(n), dx(n), dy(n), out(n);
        for (std::size_t j = 0; j < n; ++j) {
          x[j] = particles[j].x;
          y[j] = particles[j].y;
          dx[j] = std::cos(particles[j].theta + angle);
          dy[j] = std::sin(particles[j].theta + angle);
        }
        caster.CastMany(x, y, dx, dy, range_max, out);
        for (std::size_t j = 0; j < n; ++j) {
          const double ref = caster.CastDda(x[j], y[j], dx[j], dy[j], range_max);
          ASSERT_EQ(std::bit_cast<std::uint64_t>(out[j]), std::bit_cast<std::uint64_t>(ref))
              << "seed " << seed << " cloud " << cloud << " beam " << beam << " ray " << j;
          ++total;
          hits += std::isinf(ref) ? 0 : 1;
        }
      }
    }
  }
  std::printf("[ report ] %d rays from particle clouds, %d hits; all identical\n", total, hits);
  EXPECT_GT(hits, total / 3);
  EXPECT_LT(hits, total);
}

core::OccupancyGrid BoxRoom() {
  // 10 m x 10 m at 0.1 m, origin (0, 0); wall cells at x = 80 (x in [8, 8.1)).
  core::OccupancyGrid g(100, 100, 0.1, Vec2(0.0, 0.0));
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 100; ++x) g.SetProbability({x, y}, x == 80 ? 0.95 : 0.05);
  }
  return g;
}

TEST(GridRayCaster, DistanceToWhereTheRayEntersTheOccupiedCell) {
  const core::OccupancyGrid g = BoxRoom();
  const LikelihoodField f(g, {}, 30.0);
  const GridRayCaster caster(f);
  EXPECT_NEAR(caster.Cast(Vec2(2.05, 5.05), Vec2(1.0, 0.0), 30.0), 5.95, 1e-9);
  const double a = 0.5;
  EXPECT_NEAR(caster.Cast(Vec2(2.05, 1.05), Vec2(std::cos(a), std::sin(a)), 30.0),
              (8.0 - 2.05) / std::cos(a), 1e-9);
  // Starting inside an occupied cell: 0.
  EXPECT_EQ(caster.Cast(Vec2(8.05, 5.0), Vec2(1.0, 0.0), 30.0), 0.0);
  // A ray starting left of the map enters it and still finds the wall.
  EXPECT_NEAR(caster.Cast(Vec2(-2.0, 5.05), Vec2(1.0, 0.0), 30.0), 10.0, 1e-9);
}

TEST(GridRayCaster, CastManyIsBitIdenticalToDdaFromOneUlpAroundGridLines) {
  // Origins on grid lines and one ulp to either side of them, in a grid of walls (so that the
  // exact traversal often starts right at the origin): rounding may put such an origin in the
  // cell beyond the line in cell units while the crossings put it before, or the other way round.
  core::OccupancyGrid g(200, 150, 0.1, Vec2(-3.3, -1.7));
  for (int y = 0; y < 150; ++y) {
    for (int x = 0; x < 200; ++x) g.SetProbability({x, y}, x % 7 == 0 || y % 9 == 0 ? 0.95 : 0.05);
  }
  const LikelihoodField f(g, {}, 30.0);
  const GridRayCaster caster(f);
  core::Rng rng(17);
  std::vector<double> x, y, dx, dy;
  for (int k = 1; k < 200; k += 2) {
    for (int j = 1; j < 150; j += 5) {
      const double line_x = -3.3 + k * 0.1, line_y = -1.7 + j * 0.1;
      for (const double px : {std::nextafter(line_x, -1e9), line_x, std::nextafter(line_x, 1e9)}) {
        for (const double py :
             {std::nextafter(line_y, -1e9), line_y + 0.03, std::nextafter(line_y, 1e9)}) {
          const double a = rng.Uniform(-core::kPi, core::kPi);
          x.push_back(px);
          y.push_back(py);
          dx.push_back(std::cos(a));
          dy.push_back(std::sin(a));
        }
      }
    }
  }
  std::vector<double> out(x.size());
  caster.CastMany(x, y, dx, dy, 30.0, out);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double ref = caster.CastDda(x[i], y[i], dx[i], dy[i], 30.0);
    ASSERT_EQ(std::bit_cast<std::uint64_t>(out[i]), std::bit_cast<std::uint64_t>(ref))
        << "ray " << i << " from (" << x[i] << ", " << y[i] << ")";
    ASSERT_EQ(std::bit_cast<std::uint64_t>(caster.Cast(x[i], y[i], dx[i], dy[i], 30.0)),
              std::bit_cast<std::uint64_t>(ref))
        << "ray " << i;
  }
}

TEST(GridRayCaster, NoObstacleOnTheRayIsInfinityNotZero) {
  const core::OccupancyGrid g = BoxRoom();
  const LikelihoodField f(g, {}, 30.0);
  const GridRayCaster caster(f);
  // Leaves the map without meeting an occupied cell.
  EXPECT_EQ(caster.Cast(Vec2(2.0, 5.0), Vec2(-1.0, 0.0), 30.0), kNoHit);
  EXPECT_EQ(caster.CastDda(Vec2(2.0, 5.0), Vec2(-1.0, 0.0), 30.0), kNoHit);
  EXPECT_EQ(caster.Cast(Vec2(2.0, 5.0), Vec2(0.0, 1.0), 30.0), kNoHit);
  // The wall is beyond range_max.
  EXPECT_EQ(caster.Cast(Vec2(2.05, 5.0), Vec2(1.0, 0.0), 5.0), kNoHit);
  EXPECT_NEAR(caster.Cast(Vec2(2.05, 5.0), Vec2(1.0, 0.0), 5.95), 5.95, 1e-9);
  // A ray that misses the map entirely.
  EXPECT_EQ(caster.Cast(Vec2(-5.0, -5.0), Vec2(-1.0, 0.0), 30.0), kNoHit);
  EXPECT_TRUE(std::isinf(kNoHit) && kNoHit > 0.0);
  // An empty map.
  const core::OccupancyGrid empty(50, 50, 0.1, Vec2(0.0, 0.0));
  const LikelihoodField fe(empty, {}, 30.0);
  EXPECT_EQ(GridRayCaster(fe).Cast(Vec2(2.0, 2.0), Vec2(0.6, 0.8), 30.0), kNoHit);
}

}  // namespace
}  // namespace retrace::nav
