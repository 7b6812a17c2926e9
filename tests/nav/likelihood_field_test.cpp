#include "nav/likelihood_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/errors.hpp"
#include "core/rng.hpp"

namespace retrace::nav {
namespace {

using core::Vec2;

std::vector<float> BruteForce(const std::vector<std::uint8_t>& occ, int w, int h) {
  std::vector<float> out(occ.size(), std::numeric_limits<float>::infinity());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double best = std::numeric_limits<double>::infinity();
      for (int oy = 0; oy < h; ++oy) {
        for (int ox = 0; ox < w; ++ox) {
          if (occ[static_cast<std::size_t>(oy * w + ox)] == 0) continue;
          best = std::min(best, std::hypot(double(x - ox), double(y - oy)));
        }
      }
      out[static_cast<std::size_t>(y * w + x)] = static_cast<float>(best);
    }
  }
  return out;
}

TEST(DistanceTransform, ExactAgainstBruteForceOnRandomGrids) {
  for (int seed = 0; seed < 30; ++seed) {
    core::Rng rng(static_cast<std::uint64_t>(seed));
    const int w = 1 + static_cast<int>(rng.UniformIndex(40));
    const int h = 1 + static_cast<int>(rng.UniformIndex(40));
    const double density = seed % 3 == 0 ? 0.005 : (seed % 3 == 1 ? 0.05 : 0.4);
    std::vector<std::uint8_t> occ(static_cast<std::size_t>(w * h));
    for (auto& o : occ) o = rng.Bernoulli(density) ? 1 : 0;
    const std::vector<float> fast = DistanceTransformCells(occ, w, h);
    const std::vector<float> slow = BruteForce(occ, w, h);
    ASSERT_EQ(fast.size(), slow.size());
    for (std::size_t i = 0; i < fast.size(); ++i) {
      if (std::isinf(slow[i])) {
        EXPECT_TRUE(std::isinf(fast[i])) << "seed " << seed << " cell " << i;
      } else {
        EXPECT_NEAR(fast[i], slow[i], 1e-5) << "seed " << seed << " cell " << i;
      }
    }
  }
}

TEST(DistanceTransform, EmptyAndFullGrids) {
  EXPECT_TRUE(DistanceTransformCells({}, 0, 0).empty());
  const std::vector<float> none = DistanceTransformCells(std::vector<std::uint8_t>(12, 0), 4, 3);
  for (const float d : none) EXPECT_TRUE(std::isinf(d));
  const std::vector<float> all = DistanceTransformCells(std::vector<std::uint8_t>(12, 1), 4, 3);
  for (const float d : all) EXPECT_EQ(d, 0.0f);
}

core::OccupancyGrid WallGrid() {
  // 40 x 30 cells at 0.1 m, origin (-1, -2); one occupied column at cell x = 20 (x in [1, 1.1)).
  core::OccupancyGrid g(40, 30, 0.1, Vec2(-1.0, -2.0));
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) g.SetProbability({x, y}, x == 20 ? 0.95 : (x == 5 ? 0.6 : 0.05));
  }
  return g;
}

TEST(LikelihoodField, TableHoldsEquationFiveSixOfTheDistance) {
  const core::OccupancyGrid g = WallGrid();
  LikelihoodFieldConfig config;
  const LikelihoodField f(g, config, 30.0);
  EXPECT_EQ(f.width(), 40);
  EXPECT_TRUE(f.Occupied({20, 7}));
  EXPECT_FALSE(f.Occupied({5, 7}));  // 0.6 < 0.65 threshold
  EXPECT_FLOAT_EQ(f.Distance({23, 4}), 0.3f);
  // Normalisation: p(d) = z_hit N(d; 0, σ) + z_rand / range_max, d less half a cell.
  const double sigma = config.sigma_hit;
  const double d = 0.3 - 0.05;
  const double expected = std::log(config.z_hit * std::exp(-d * d / (2 * sigma * sigma)) /
                                        (std::sqrt(2 * std::numbers::pi) * sigma) +
                                    config.z_rand / 30.0);
  EXPECT_NEAR(f.LogLikelihood(g.CellToWorld({23, 4})), expected, 1e-5);
  EXPECT_NEAR(f.LogLikelihood(g.CellToWorld({20, 4})), f.LogLikelihoodOfDistance(0.0), 1e-6);
  // Truncated at max_distance: far cells equal the z_rand-only value up to the Gaussian tail.
  EXPECT_NEAR(f.LogLikelihood(g.CellToWorld({0, 0})), std::log(config.z_rand / 30.0), 1e-6);
  // Outside the map: the z_rand-only value.
  EXPECT_FLOAT_EQ(f.LogLikelihood(Vec2(-5.0, 0.0)), f.OutsideLogLikelihood());
  EXPECT_FLOAT_EQ(f.OutsideLogLikelihood(), static_cast<float>(std::log(0.05 / 30.0)));
  EXPECT_FLOAT_EQ(f.LogLikelihood(Vec2(3.0001, 0.0)), f.OutsideLogLikelihood());
  // Nearer is likelier.
  EXPECT_GT(f.LogLikelihood(g.CellToWorld({21, 4})), f.LogLikelihood(g.CellToWorld({24, 4})));
}

TEST(LikelihoodField, SumEqualsPerPointLookups) {
  const core::OccupancyGrid g = WallGrid();
  const LikelihoodField f(g, {}, 30.0);
  core::Rng rng(3);
  std::vector<double> xs, ys;
  for (int i = 0; i < 200; ++i) {
    xs.push_back(rng.Uniform(-4.0, 4.0));
    ys.push_back(rng.Uniform(-4.0, 4.0));
  }
  for (int k = 0; k < 50; ++k) {
    const core::Pose2 X(rng.Uniform(-1.0, 3.0), rng.Uniform(-2.0, 1.0), rng.Uniform(-3.0, 3.0));
    double expected = 0.0;
    for (std::size_t i = 0; i < xs.size(); ++i) expected += f.LogLikelihood(X * Vec2(xs[i], ys[i]));
    EXPECT_EQ(f.SumLogLikelihood(X, xs.data(), ys.data(), xs.size()), expected);
  }
}

TEST(LikelihoodField, ConfigErrorsNameTheKey) {
  const core::OccupancyGrid g = WallGrid();
  LikelihoodFieldConfig c;
  c.sigma_hit = 0.0;
  try {
    LikelihoodField f(g, c, 30.0);
    FAIL();
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "sigma_hit");
  }
  c = {};
  c.occupied_threshold = 0.4;
  EXPECT_THROW(LikelihoodField(g, c, 30.0), core::ConfigError);
  EXPECT_THROW(LikelihoodField(g, {}, 0.0), core::ConfigError);
}

TEST(LikelihoodField, EmptyMapIsAllOutside) {
  const core::OccupancyGrid g;
  const LikelihoodField f(g, {}, 30.0);
  const double xs[2] = {1.0, 2.0}, ys[2] = {0.0, 0.0};
  EXPECT_FLOAT_EQ(f.LogLikelihood(Vec2(0.0, 0.0)), f.OutsideLogLikelihood());
  EXPECT_DOUBLE_EQ(f.SumLogLikelihood(core::Pose2(), xs, ys, 2), 2.0 * f.OutsideLogLikelihood());
}

}  // namespace
}  // namespace retrace::nav
