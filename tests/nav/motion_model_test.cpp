#include "nav/motion_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "tests/support/config_key.hpp"

namespace retrace::nav {
namespace {

using retrace::testing::ValidationErrorKey;

struct Spread {
  double var_x, var_y, var_theta;
};

// Moves 2000 particles along a 2 m arc turning 0.5 rad, in `steps` equal increments.
Spread SpreadAfter(int steps, std::uint64_t seed) {
  const MotionModelConfig config;
  core::Rng rng(seed);
  const core::OdometryDelta step{2.0 / steps, 0.5 / steps};
  const MotionNoise noise = MotionNoiseOf(step, config);
  const int n = 2000;
  std::vector<core::Pose2> ps(n);
  for (auto& p : ps) {
    for (int k = 0; k < steps; ++k) p = SampleMotion(p, step, noise, rng);
  }
  double mx = 0, my = 0, mt = 0;
  for (const auto& p : ps) {
    mx += p.x / n;
    my += p.y / n;
    mt += p.theta / n;
  }
  Spread s{0, 0, 0};
  for (const auto& p : ps) {
    s.var_x += (p.x - mx) * (p.x - mx) / (n - 1);
    s.var_y += (p.y - my) * (p.y - my) / (n - 1);
    s.var_theta += (p.theta - mt) * (p.theta - mt) / (n - 1);
  }
  return s;
}

TEST(MotionModel, SpreadDependsOnTheMotionNotOnTheStepSize) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const Spread one = SpreadAfter(1, seed);
    const Spread many = SpreadAfter(100, seed + 10);
    // Heading variance: α1 |δrot| + α2 |δtrans| summed over the path, whatever the steps.
    const MotionModelConfig c;
    const double expected_theta = c.alpha1 * 0.5 + c.alpha2 * 2.0;
    EXPECT_NEAR(one.var_theta / expected_theta, 1.0, 0.15);
    EXPECT_NEAR(many.var_theta / expected_theta, 1.0, 0.15);
    // Position spread of the same order (the path's shape redistributes it between x and y).
    const double pos_one = one.var_x + one.var_y, pos_many = many.var_x + many.var_y;
    EXPECT_NEAR(pos_many / pos_one, 1.0, 0.35) << pos_one << " " << pos_many;
  }
}

TEST(MotionModel, ZeroMotionLeavesThePoseAndDrawsNothing) {
  core::Rng a(5), b(5);
  const core::Pose2 X(1.0, 2.0, 0.3);
  const core::OdometryDelta zero{0.0, 0.0};
  EXPECT_EQ(SampleMotion(X, zero, MotionNoiseOf(zero, {}), a), X);
  EXPECT_EQ(a.NextU64(), b.NextU64());
}

TEST(MotionModel, MeanFollowsEquationTwo) {
  core::Rng rng(7);
  const core::OdometryDelta d{0.5, 0.2};
  const MotionNoise noise = MotionNoiseOf(d, {});
  const core::Pose2 expected = core::IntegrateOdometry(core::Pose2(), d);
  double mx = 0, my = 0, mt = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const core::Pose2 p = SampleMotion(core::Pose2(), d, noise, rng);
    mx += p.x / n;
    my += p.y / n;
    mt += p.theta / n;
  }
  EXPECT_NEAR(mx, expected.x, 2e-3);
  EXPECT_NEAR(my, expected.y, 2e-3);
  EXPECT_NEAR(mt, expected.theta, 2e-3);
}

TEST(MotionModel, ConfigErrorsNameTheKey) {
  MotionModelConfig c;
  c.alpha2 = -1.0;
  EXPECT_EQ(ValidationErrorKey(c), "alpha2");
}

}  // namespace
}  // namespace retrace::nav
