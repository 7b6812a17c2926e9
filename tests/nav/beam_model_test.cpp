#include "nav/beam_model.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/errors.hpp"
#include "core/rng.hpp"
#include "nav/dynamic_beam_test.hpp"

namespace retrace::nav {
namespace {

using core::Vec2;

// ∫_0^range_max p_beam(z | z*) dz (midpoint rule) plus the probability mass at range_max.
double Integral(const BeamModel& m, double z_star) {
  const double r = m.range_max();
  const int n = 600000;
  const double h = r / n;
  double s = 0.0;
  for (int i = 0; i < n; ++i) s += m.Evaluate((i + 0.5) * h, z_star).total * h;
  const BeamModelConfig& c = m.config();
  const double max_mass = c.z_max / (c.z_hit + c.z_short + c.z_max + c.z_rand);
  EXPECT_GE(m.Evaluate(r, z_star).total, max_mass);  // the point mass sits at range_max
  return s + max_mass;
}

TEST(BeamModel, IntegratesToOne) {
  const BeamModel m({}, 30.0);
  for (const double z_star : {0.05, 0.3, 1.0, 5.0, 15.0, 29.7, 30.0, kNoHit}) {
    EXPECT_NEAR(Integral(m, z_star), 1.0, 2e-4) << "z* = " << z_star;
  }
  // z* = 0 (inside an obstacle) leaves no room for a short reading: its mass is missing.
  const BeamModelConfig d;
  EXPECT_NEAR(Integral(m, 0.0), 1.0 - d.z_short / (d.z_hit + d.z_short + d.z_max + d.z_rand), 2e-4);
  BeamModelConfig c;
  c.lambda_short = 2.0;
  c.sigma_hit = 0.5;
  const BeamModel m2(c, 10.0);
  for (const double z_star : {0.2, 3.0, 9.9, kNoHit}) {
    EXPECT_NEAR(Integral(m2, z_star), 1.0, 2e-4) << "z* = " << z_star;
  }
}

TEST(BeamModel, TermsFollowTheEquations) {
  const BeamModelConfig c;
  const BeamModel m(c, 30.0);
  const double sum = c.z_hit + c.z_short + c.z_max + c.z_rand;
  const double z = 2.0, zs = 5.0;
  const BeamModel::Terms t = m.Evaluate(z, zs);
  const double p_short = c.lambda_short * std::exp(-c.lambda_short * z) /
                         (1.0 - std::exp(-c.lambda_short * zs));  // eq. (8)
  EXPECT_NEAR(t.short_part, c.z_short / sum * p_short, 1e-12);
  const double a = (z - zs) / c.sigma_hit;
  const double p_hit = std::exp(-0.5 * a * a) / (std::sqrt(2 * M_PI) * c.sigma_hit);
  EXPECT_NEAR(t.total, t.short_part + c.z_hit / sum * p_hit + c.z_rand / sum / 30.0, 1e-12);
  // No short reading beyond z*, and none when the sensor sits in an obstacle (z* = 0).
  EXPECT_EQ(m.Evaluate(6.0, zs).short_part, 0.0);
  EXPECT_EQ(m.Evaluate(0.5, 0.0).short_part, 0.0);
  EXPECT_TRUE(std::isfinite(m.Evaluate(0.01, 1e-9).total));
  // The max-range mass.
  EXPECT_NEAR(m.Evaluate(30.0, 10.0).total - m.Evaluate(29.99, 10.0).total, c.z_max / sum, 1e-3);
  // EvaluateFast is Evaluate with the decay precomputed.
  EXPECT_EQ(m.EvaluateFast(z, m.ShortDecay(z), zs).total, t.total);
}

TEST(BeamModel, SumTermsIsBitIdenticalToSummingEvaluateFast) {
  // Expected ranges of every kind: no hit, beyond and at range_max, 0 and negative, within 0.9 m
  // of either end (where the hit normaliser is not 1), on both sides of the reading and far
  // from it (the Gaussian underflows); readings in range, at and beyond range_max, and below 0.
  core::Rng rng(5);
  const BeamModel m({}, 30.0);
  std::vector<double> z_star = {kNoHit, 30.0, 45.0, 0.0, -0.0, -1.0, 0.01, 0.5, 29.5, 29.99};
  for (int i = 0; i < 500; ++i) {
    z_star.push_back(i % 3 == 0 ? rng.Uniform(0.0, 30.0) : 5.0 + 0.3 * rng.Normal());
  }
  std::vector<double> weights(z_star.size());
  for (double& w : weights) w = rng.Uniform(0.0, 1.0);
  BeamModel::Scratch scratch;
  for (const double z : {5.0, 5.2, 0.3, 29.8, 30.0, 31.0, 0.0, -1.0}) {
    for (const bool weighted : {false, true}) {
      double sum_short = 0.0, sum_total = 0.0;
      for (std::size_t i = 0; i < z_star.size(); ++i) {
        const double w = weighted ? weights[i] : 1.0;
        const BeamModel::Terms t = m.EvaluateFast(z, m.ShortDecay(z), z_star[i]);
        sum_short += w * t.short_part;
        sum_total += w * t.total;
      }
      const BeamModel::Terms sums = m.SumTerms(
          z, m.ShortDecay(z), z_star, weighted ? weights : std::vector<double>{}, &scratch);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(sums.short_part),
                std::bit_cast<std::uint64_t>(sum_short))
          << "z = " << z << (weighted ? " weighted" : "");
      EXPECT_EQ(std::bit_cast<std::uint64_t>(sums.total), std::bit_cast<std::uint64_t>(sum_total))
          << "z = " << z << (weighted ? " weighted" : "");
    }
  }
  EXPECT_EQ(m.SumTerms(5.0, m.ShortDecay(5.0), {}, {}, &scratch).total, 0.0);
}

TEST(BeamModel, NoObstacleOnTheRayMeansExpectedRangeIsRangeMax) {
  const BeamModelConfig c;
  const BeamModel m(c, 30.0);
  for (const double z : {0.5, 3.0, 12.0, 29.9}) {
    const BeamModel::Terms none = m.Evaluate(z, kNoHit);
    const BeamModel::Terms at_max = m.Evaluate(z, 30.0);
    EXPECT_EQ(none.short_part, at_max.short_part);
    EXPECT_EQ(none.total, at_max.total);
    EXPECT_GT(none.short_part, 0.0);  // a return where the map has nothing counts as short
  }
  // With the defaults a reading well short of max range on an empty ray is mostly "short":
  // ratio = s / (s + z_rand/range_max) with s = z_short λ e^{-λz} / (1 - e^{-λ range_max}).
  const double sum = c.z_hit + c.z_short + c.z_max + c.z_rand;
  const double s = c.z_short / sum * c.lambda_short * std::exp(-c.lambda_short * 3.0) /
                   (1.0 - std::exp(-c.lambda_short * 30.0));
  const BeamModel::Terms t = m.Evaluate(3.0, kNoHit);
  EXPECT_NEAR(t.short_part / t.total, s / (s + c.z_rand / sum / 30.0), 1e-9);
  EXPECT_GT(t.short_part / t.total, 0.9);
}

core::OccupancyGrid EmptyRoomRightWall() {
  // 20 m x 20 m at 0.1 m, origin (-10, -10); a wall at x in [3, 3.1).
  core::OccupancyGrid g(200, 200, 0.1, Vec2(-10.0, -10.0));
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 200; ++x) g.SetProbability({x, y}, x == 130 ? 0.95 : 0.05);
  }
  return g;
}

core::LaserScan FourBeams(float a, float b, float c, float d) {
  core::LaserScan scan;
  scan.angle_min = 0.0;  // beam 0 along +x (toward the wall), beam 2 along -x (open space)
  scan.angle_increment = M_PI / 2.0;
  scan.range_min = 0.05;
  scan.range_max = 30.0;
  scan.ranges = {a, b, c, d};
  return scan;
}

// Every ray cast to range_max and every ratio computed, with each ray caster.
const DynamicTestOptions kAllRatios{RayCastMethod::kSphereTracing, false};
const DynamicTestOptions kAllRatiosDda{RayCastMethod::kDda, false};

TEST(DynamicBeams, ShortReadingsInFrontOfMappedWallsAndInOpenSpaceAreDynamic) {
  const core::OccupancyGrid g = EmptyRoomRightWall();
  const LikelihoodField f(g, {}, 30.0);
  const GridRayCaster caster(f);
  const BeamModel model({}, 30.0);
  core::Rng rng(1);
  std::vector<core::Pose2> X_ML;
  for (int j = 0; j < 200; ++j) X_ML.emplace_back(0.03 * rng.Normal(), 0.03 * rng.Normal(), 0.01 * rng.Normal());
  const std::vector<int> beams = {0, 1, 2};
  DynamicBeamResult r;
  // Beam 0 sees the wall at 3 m: static. Beam 1 (+y) and beam 2 (-x) meet no mapped obstacle:
  // a return at 1.5 m is something unmapped: dynamic.
  TestDynamicBeams(model, caster, X_ML, {}, FourBeams(3.0f, 1.5f, 1.5f, 1.0f), beams, 0.9,
                   kAllRatios, &r);
  ASSERT_EQ(r.dynamic.size(), 3u);
  EXPECT_EQ(r.dynamic[0], 0);
  EXPECT_EQ(r.dynamic[1], 1);
  EXPECT_EQ(r.dynamic[2], 1);
  EXPECT_LT(r.ratio[0], 0.05);
  // A pedestrian 1 m in front of the wall: dynamic.
  TestDynamicBeams(model, caster, X_ML, {}, FourBeams(2.0f, 1.5f, 1.5f, 1.0f), beams, 0.9,
                   kAllRatios, &r);
  EXPECT_EQ(r.dynamic[0], 1);
  // The reference ray caster gives the same ratios bit for bit.
  DynamicBeamResult ref;
  TestDynamicBeams(model, caster, X_ML, {}, FourBeams(2.0f, 1.5f, 1.5f, 1.0f), beams, 0.9,
                   kAllRatiosDda, &ref);
  EXPECT_EQ(ref.ratio, r.ratio);
  EXPECT_EQ(ref.dynamic, r.dynamic);
  // Weights: equal weights give the unweighted sums; a zero weight removes a particle.
  std::vector<double> w(X_ML.size(), 1.0 / static_cast<double>(X_ML.size()));
  DynamicBeamResult weighted;
  TestDynamicBeams(model, caster, X_ML, w, FourBeams(2.0f, 1.5f, 1.5f, 1.0f), beams, 0.9,
                   kAllRatios, &weighted);
  for (std::size_t b = 0; b < beams.size(); ++b) EXPECT_NEAR(weighted.ratio[b], r.ratio[b], 1e-12);
}

TEST(BeamModel, ConfigErrorsNameTheKey) {
  BeamModelConfig c;
  c.lambda_short = 0.0;
  try {
    BeamModel m(c, 30.0);
    FAIL();
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "lambda_short");
  }
  c = {};
  c.z_hit = c.z_short = c.z_max = c.z_rand = 0.0;
  EXPECT_THROW(BeamModel(c, 30.0), core::ConfigError);
  EXPECT_THROW(BeamModel({}, std::numeric_limits<double>::infinity()), core::ConfigError);
}

}  // namespace
}  // namespace retrace::nav
