#include "nav/measurement_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/errors.hpp"
#include "core/rng.hpp"

namespace retrace::nav {
namespace {

using core::Vec2;

// 40 x 30 cells at 0.1 m, origin (-1, -2); one occupied column at x in [1, 1.1).
core::OccupancyGrid WallGrid() {
  core::OccupancyGrid g(40, 30, 0.1, Vec2(-1.0, -2.0));
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) g.SetProbability({x, y}, x == 20 ? 0.95 : 0.05);
  }
  return g;
}

WeighedPoints RandomPoints(core::Rng& rng, bool class_conditional) {
  const ClassConditionalConfig cc;
  WeighedPoints p;
  if (class_conditional) p.mapped_prior = cc.mapped_prior;
  for (int i = 0; i < 100; ++i) {
    p.Add(rng.Uniform(-4.0, 4.0), rng.Uniform(-4.0, 4.0));
    // Every tenth point may not be unknown (it sees through a wall).
    const double r = std::hypot(p.xs.back(), p.ys.back());
    if (class_conditional) p.unknown.push_back(i % 10 == 0 ? 0.0 : cc.UnknownDensity(r, 30.0));
  }
  return p;
}

TEST(MeasurementModel, ThePapersModelIsTheLikelihoodFieldOnTheKeptPoints) {
  const LikelihoodField f(WallGrid(), {}, 30.0);
  core::Rng rng(1);
  const WeighedPoints p = RandomPoints(rng, false);
  const core::Pose2 X(0.3, -0.2, 0.7);
  EXPECT_EQ(ScanLogLikelihood(f, X, p), f.SumLogLikelihood(X, p.xs.data(), p.ys.data(), p.size()));
}

TEST(MeasurementModel, ClassConditionalIsTheMixtureOfBothClassesPerPoint) {
  const LikelihoodField f(WallGrid(), {}, 30.0);
  core::Rng rng(2);
  const WeighedPoints p = RandomPoints(rng, true);
  for (int k = 0; k < 20; ++k) {
    const core::Pose2 X(rng.Uniform(-1.0, 3.0), rng.Uniform(-2.0, 1.0), rng.Uniform(-3.0, 3.0));
    double expected = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double mapped = std::exp(f.LogLikelihood(X * Vec2(p.xs[i], p.ys[i])));
      expected += std::log(p.mapped_prior * mapped + p.unknown[i]);
    }
    EXPECT_NEAR(ScanLogLikelihood(f, X, p), expected, 1e-9 * std::abs(expected));
  }
}

TEST(MeasurementModel, TheUnknownClassExplainsAShortReadingInFreeSpaceNotOneOnAWall) {
  // LiDAR at the origin facing +x; the wall's face is at x = 1.
  const LikelihoodField f(WallGrid(), {}, 30.0);
  const ClassConditionalConfig cc;
  WeighedPoints p;
  p.mapped_prior = cc.mapped_prior;
  p.Add(0.2, 0.0);  // a person 0.8 m before the wall
  p.unknown.push_back(cc.UnknownDensity(0.2, 30.0));
  p.Add(1.0, 0.0);  // the wall
  p.unknown.push_back(cc.UnknownDensity(1.0, 30.0));
  p.Add(2.5, 0.0);  // beyond the wall: not unknown (a person cannot lengthen a beam)
  p.unknown.push_back(0.0);
  const std::vector<double> post = UnknownPosterior(f, core::Pose2(), p);
  EXPECT_GT(post[0], cc.unknown_threshold);
  EXPECT_LT(post[1], 0.1);
  EXPECT_EQ(post[2], 0.0);
}

TEST(MeasurementModel, TheUnknownDensityIsATruncatedExponential) {
  ClassConditionalConfig cc;
  cc.mapped_prior = 0.25;
  cc.lambda_unknown = 0.2;
  // (1 - π) ∫_0^range_max p_u = 1 - π.
  double integral = 0.0;
  const double dz = 1e-3;
  for (double z = 0.5 * dz; z < 10.0; z += dz) integral += cc.UnknownDensity(z, 10.0) * dz;
  EXPECT_NEAR(integral, 0.75, 1e-6);
  EXPECT_GT(cc.UnknownDensity(1.0, 10.0), cc.UnknownDensity(5.0, 10.0));
}

TEST(MeasurementModel, ConfigErrorsNameTheKey) {
  const auto key_of = [](const ClassConditionalConfig& c) {
    try {
      c.Validate();
    } catch (const core::ConfigError& e) {
      return e.key_path();
    }
    return std::string();
  };
  ClassConditionalConfig c;
  EXPECT_EQ(key_of(c), "");
  c.mapped_prior = 0.0;
  EXPECT_EQ(key_of(c), "mapped_prior");
  c = {};
  c.lambda_unknown = -1.0;
  EXPECT_EQ(key_of(c), "lambda_unknown");
  c = {};
  c.unknown_threshold = 1.5;
  EXPECT_EQ(key_of(c), "unknown_threshold");
}

}  // namespace
}  // namespace retrace::nav
