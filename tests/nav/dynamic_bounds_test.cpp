// The dynamic-point test decided by bounds (nav/dynamic_beam_test.hpp) against the test that
// casts every ray to range_max and computes every ratio: the same mask, always.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <span>
#include <vector>

#include "core/angle.hpp"
#include "core/rng.hpp"
#include "nav/beam_model.hpp"
#include "nav/dynamic_beam_test.hpp"

namespace retrace::nav {
namespace dynamic_bounds_test {

// A 25 m x 20 m grid at 0.1 m: a room outline open on one side (rays leave the map) and blobs.
core::OccupancyGrid BlobMap(std::uint64_t seed) {
  core::OccupancyGrid g(250, 200, 0.1, core::Vec2(-5.0, -5.0));
  core::Rng rng(seed);
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 250; ++x) {
      const bool wall = (y == 5 || y == 195 || x == 5) && !(y > 80 && y < 110);
      g.SetProbability({x, y}, wall ? 0.95 : 0.05);
    }
  }
  for (int k = 0; k < 30; ++k) {
    const int cx = static_cast<int>(rng.UniformIndex(250)),
              cy = static_cast<int>(rng.UniformIndex(200));
    const int r = static_cast<int>(rng.UniformIndex(5));
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

TEST(DynamicBounds, TermBoundsHoldEveryExpectedRangeBeyondTheirLimit) {
  core::Rng rng(7);
  int checked = 0;
  for (const double sigma : {0.02, 0.1, 0.5}) {
    for (const double lambda : {0.05, 1.0}) {
      BeamModelConfig c;
      c.sigma_hit = sigma;
      c.lambda_short = lambda;
      const BeamModel model(c, 30.0);
      for (int i = 0; i < 4000; ++i) {
        const double z = i % 50 == 0 ? 30.0 + rng.Uniform(0.0, 1.0) : rng.Uniform(0.0, 30.0);
        const double lo = i % 3 == 0 ? -1.0 : rng.Uniform(0.0, 31.0);
        const double decay = model.ShortDecay(z);
        const BeamModel::TermBounds b = model.BoundsBeyond(z, decay, lo);
        for (int k = 0; k < 20; ++k) {
          // z* anywhere in (lo, range_max], near the ends and z, or no hit at all.
          double zs = rng.Uniform(std::max(lo, 0.0), 30.0);
          if (k == 0) zs = kNoHit;
          if (k == 1) zs = std::nextafter(std::max(lo, 0.0), 31.0);
          if (k == 2 && z > std::max(lo, 0.0) && z <= 30.0) zs = z;
          if (zs <= lo) continue;
          const BeamModel::Terms t = model.EvaluateFast(z, decay, zs);
          const double rest = t.total - t.short_part;
          const double tol = 1e-12 * (t.total + 1e-300);
          ASSERT_LE(b.short_lo, t.short_part + tol) << "z " << z << " lo " << lo << " z* " << zs;
          ASSERT_GE(b.short_hi, t.short_part - tol) << "z " << z << " lo " << lo << " z* " << zs;
          ASSERT_LE(b.rest_lo, rest + tol) << "z " << z << " lo " << lo << " z* " << zs;
          ASSERT_GE(b.rest_hi, rest - tol) << "z " << z << " lo " << lo << " z* " << zs;
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 400000);
}

TEST(DynamicBounds, ACastStoppedShortGivesTheSameHitOrNone) {
  const core::OccupancyGrid g = BlobMap(3);
  const LikelihoodField f(g, {}, 30.0);
  const GridRayCaster caster(f);
  core::Rng rng(11);
  std::vector<double> x(256), y(256), dx(256), dy(256), full(256), part(256);
  for (int round = 0; round < 40; ++round) {
    const double limit = rng.Uniform(0.0, 12.0);
    for (std::size_t k = 0; k < x.size(); ++k) {
      x[k] = rng.Uniform(-6.0, 21.0);
      y[k] = rng.Uniform(-6.0, 16.0);
      const double a = rng.Uniform(-core::kPi, core::kPi);
      dx[k] = std::cos(a);
      dy[k] = std::sin(a);
    }
    caster.CastMany(x, y, dx, dy, 30.0, full);
    caster.CastMany(x, y, dx, dy, limit, part);
    for (std::size_t k = 0; k < x.size(); ++k) {
      const double expected = full[k] <= limit ? full[k] : kNoHit;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(part[k]), std::bit_cast<std::uint64_t>(expected))
          << "round " << round << " ray " << k;
    }
  }
}

// A scan of 109 beams over 270° from `truth` on the map: the map's ranges with 2 cm noise, a
// third of the beams cut short (people), some beyond the map's walls, open space read at random.
core::LaserScan SceneScan(const GridRayCaster& caster, const core::Pose2& truth, core::Rng& rng) {
  core::LaserScan scan;
  scan.angle_min = -0.75 * core::kPi;
  scan.angle_increment = 1.5 * core::kPi / 108.0;
  scan.range_min = 0.05;
  scan.range_max = 30.0;
  for (std::size_t i = 0; i < 109; ++i) {
    const double a = truth.theta + scan.Angle(i);
    double z = caster.CastDda(truth.x, truth.y, std::cos(a), std::sin(a), 30.0);
    if (z == kNoHit) z = rng.Uniform(1.0, 29.0);
    const double u = rng.Uniform();
    if (u < 0.33)
      z = rng.Uniform(0.2, z);
    else if (u < 0.40)
      z += rng.Uniform(0.0, 3.0);
    z = std::clamp(z + 0.02 * rng.Normal(), 0.06, 29.9);
    scan.ranges.push_back(static_cast<float>(z));
  }
  return scan;
}

// Particles around `truth`: a tight, a loose, a wide or a two-headed cloud.
std::vector<core::Pose2> Cloud(const core::Pose2& truth, int kind, core::Rng& rng) {
  const double spread[] = {0.02, 0.2, 1.0, 0.05};
  std::vector<core::Pose2> X;
  for (int j = 0; j < 300; ++j) {
    const double s = spread[kind];
    const double shift = kind == 3 && j % 2 == 1 ? 1.5 : 0.0;
    X.emplace_back(truth.x + shift + s * rng.Normal(), truth.y + s * rng.Normal(),
                   truth.theta + 0.3 * s * rng.Normal());
  }
  return X;
}

// How the beams of TheMaskIsTheSameAsWithEveryRatioComputed were decided.
struct DecisionCounts {
  int decided = 0, exact = 0, dynamic = 0, near_chi = 0, total = 0;
};

// One scene and cloud with one ray-cast method: every ratio computed once (the mask for a χ is
// the ratios above it, as the test decides a beam whose ratio it computes), then the test by
// bounds at χ as given and at χ on one beam's own ratio give or take a rounding, where no bound
// can decide that beam and the exact sums must. `near_beam` picks that beam.
void ExpectTheMaskOfEveryRatio(const BeamModel& model, const GridRayCaster& caster,
                               std::span<const core::Pose2> X, std::span<const double> w,
                               const core::LaserScan& scan, RayCastMethod method,
                               std::size_t near_beam, DecisionCounts* counts) {
  std::vector<int> beams(scan.size());
  for (std::size_t i = 0; i < beams.size(); ++i) beams[i] = static_cast<int>(i);
  DynamicBeamResult all, bounded;
  TestDynamicBeams(model, caster, X, w, scan, beams, 0.9, {method, false}, &all);
  const double near = all.ratio[near_beam % beams.size()];
  for (const double chi : {0.9, 0.5, near, std::nextafter(near, 0.0)}) {
    std::vector<std::uint8_t> mask(beams.size());
    for (std::size_t b = 0; b < beams.size(); ++b) mask[b] = all.ratio[b] > chi ? 1 : 0;
    if (chi == 0.9) {
      ASSERT_EQ(mask, all.dynamic);
    }
    TestDynamicBeams(model, caster, X, w, scan, beams, chi, {method, true}, &bounded);
    ASSERT_EQ(bounded.dynamic, mask) << "chi " << chi;
    for (std::size_t b = 0; b < beams.size(); ++b) {
      ++counts->total;
      counts->dynamic += mask[b];
      if (std::isnan(bounded.ratio[b])) {
        ++counts->decided;
        continue;
      }
      ++counts->exact;
      counts->near_chi += chi == near ? 1 : 0;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(bounded.ratio[b]),
                std::bit_cast<std::uint64_t>(all.ratio[b]));
    }
  }
}

TEST(DynamicBounds, TheMaskIsTheSameAsWithEveryRatioComputed) {
  DecisionCounts c;
  for (std::uint64_t seed = 0; seed < 3; ++seed) {
    const core::OccupancyGrid g = BlobMap(seed);
    const LikelihoodField f(g, {}, 30.0);
    const GridRayCaster caster(f);
    const BeamModel model({}, 30.0);
    core::Rng rng(seed + 50);
    for (int trial = 0; trial < 16; ++trial) {
      const core::Pose2 truth(rng.Uniform(1.0, 18.0), rng.Uniform(1.0, 13.0),
                              rng.Uniform(-core::kPi, core::kPi));
      const core::LaserScan scan = SceneScan(caster, truth, rng);
      const std::vector<core::Pose2> X = Cloud(truth, trial % 4, rng);
      std::vector<double> w;
      if (trial % 3 == 1) {
        for (std::size_t j = 0; j < X.size(); ++j) w.push_back(j % 7 == 0 ? 0.0 : rng.Uniform());
      }
      // The reference casts give the same ranges bit for bit (GridRayCaster's tests), so they
      // run on the first map only: the slow leg under the sanitizers.
      std::vector<RayCastMethod> methods = {RayCastMethod::kSphereTracing};
      if (seed == 0) methods.push_back(RayCastMethod::kDda);
      for (const RayCastMethod method : methods) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed << " trial " << trial);
        ExpectTheMaskOfEveryRatio(model, caster, X, w, scan, method,
                                  static_cast<std::size_t>(trial), &c);
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  }
  std::printf(
      "[ report ] %d beam tests: %d decided by bounds, %d by the exact sums (%d at a chi "
      "on their own ratio), %d dynamic\n",
      c.total, c.decided, c.exact, c.near_chi, c.dynamic);
  EXPECT_GT(c.decided, c.total / 2);
  EXPECT_GT(c.exact, 100);
  EXPECT_GT(c.near_chi, 40);
  EXPECT_GT(c.dynamic, c.total / 5);
}

}  // namespace dynamic_bounds_test
}  // namespace retrace::nav
