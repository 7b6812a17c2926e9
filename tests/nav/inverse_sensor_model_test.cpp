#include "nav/inverse_sensor_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "core/occupancy_grid.hpp"
#include "tests/support/config_key.hpp"

namespace retrace::nav {
namespace {

using retrace::testing::kValid;
using retrace::testing::ValidationErrorKey;

TEST(InverseSensorModel, DefaultsRaiseAHitTo094AndLowerAMissTo004) {
  const InverseSensorModelConfig config;
  EXPECT_DOUBLE_EQ(OccupancyProbability(config, 0.0), 0.94);
  EXPECT_DOUBLE_EQ(OccupancyProbability(config, -1.0), 0.04);
  EXPECT_DOUBLE_EQ(OccupancyProbability(config, -config.ReachBehind() - 1e-9), 0.04);
  EXPECT_DOUBLE_EQ(OccupancyProbability(config, 1.0), 0.5);  // behind: no information
  EXPECT_DOUBLE_EQ(HitLogOdds(config), core::Logit(0.94));
  EXPECT_DOUBLE_EQ(MissLogOdds(config), core::Logit(0.04));
  EXPECT_DOUBLE_EQ(LogOddsUpdate(config, 0.0), core::Logit(0.94));
  EXPECT_DOUBLE_EQ(LogOddsUpdate(config, 1.0), 0.0);
}

TEST(InverseSensorModel, FallsOffWithTheDistanceToTheEndPointOnBothSides) {
  const InverseSensorModelConfig config;
  double previous_front = OccupancyProbability(config, 0.0);
  double previous_back = previous_front;
  for (double d = 0.001; d <= config.ReachBehind(); d += 0.001) {
    const double front = OccupancyProbability(config, -d);
    const double back = OccupancyProbability(config, d);
    EXPECT_LT(front, previous_front) << d;
    EXPECT_LT(back, previous_back) << d;
    EXPECT_GE(front, config.miss_probability);
    EXPECT_GE(back, 0.5);
    previous_front = front;
    previous_back = back;
  }
  // eq. (6): the hit term at one sigma in front is exp(-1/2) of the way from p_miss to p_hit.
  const double one_sigma = OccupancyProbability(config, -config.sigma);
  EXPECT_NEAR(one_sigma, 0.04 + 0.9 * std::exp(-0.5), 1e-12);
  // Nearly continuous where the neighbourhood ends in front: exp(-9/2) of the span is left.
  EXPECT_NEAR(OccupancyProbability(config, -config.ReachBehind() + 1e-12), 0.04, 0.011);
}

TEST(InverseSensorModel, SignedDistanceIsZeroOnTheEndCellAndSignedAround) {
  EXPECT_DOUBLE_EQ(SignedDistanceToEndPoint(2.95, 3.05, 3.0), 0.0);
  EXPECT_DOUBLE_EQ(SignedDistanceToEndPoint(3.0, 3.1, 3.0), 0.0);
  EXPECT_NEAR(SignedDistanceToEndPoint(2.8, 2.9, 3.0), -0.1, 1e-12);
  EXPECT_NEAR(SignedDistanceToEndPoint(3.04, 3.14, 3.0), 0.04, 1e-12);
}

TEST(InverseSensorModel, FromTheLikelihoodFieldReproducesTheOriginalConstants) {
  // The original's z_hit 0.9, z_rand 0.05, 2 sigma^2 = 0.08, d_max 0.5 m, range_max 30 m.
  const InverseSensorModelConfig config =
      InverseModelFromLikelihoodField(0.9, 0.05, 0.2, 0.5, 30.0);
  EXPECT_NEAR(config.hit_probability, 0.94121, 1e-5);
  EXPECT_NEAR(config.miss_probability, 0.04121, 1e-5);
  EXPECT_DOUBLE_EQ(config.sigma, 0.2);
  EXPECT_THROW(InverseModelFromLikelihoodField(0.3, 0.05, 0.2, 0.5, 30.0), core::ConfigError);
}

TEST(InverseSensorModel, ValidateNamesTheKey) {
  InverseSensorModelConfig c;
  EXPECT_EQ(ValidationErrorKey(c), kValid);
  c.hit_probability = 0.5;
  EXPECT_EQ(ValidationErrorKey(c), "hit_probability");
  c = {};
  c.miss_probability = 0.6;
  EXPECT_EQ(ValidationErrorKey(c), "miss_probability");
  c = {};
  c.sigma = 0.0;
  EXPECT_EQ(ValidationErrorKey(c), "sigma");
  c = {};
  c.neighbourhood_sigmas = -1.0;
  EXPECT_EQ(ValidationErrorKey(c), "neighbourhood_sigmas");
}

}  // namespace
}  // namespace retrace::nav
