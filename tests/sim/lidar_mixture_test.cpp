// The simulated LiDAR draws the four-part beam mixture it is given (docs/METHOD.md, "The
// simulated LiDAR's mixture"): the histogram of many readings against a known wall matches the
// mixture's probabilities by a chi-square test, for a fixed list of seeds.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/lidar.hpp"
#include "tests/support/config_key.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::ValidationErrorKey;

constexpr double kWall = 8.0;  // m, the radius of the round room around the sensor

LidarConfig MixtureLidar() {
  LidarConfig config;
  config.range_min = 0.05;
  config.range_max = 30.0;
  config.noise.sigma0 = 0.05;
  config.noise.sigma1 = 0.0;
  config.noise.dropout_probability = 0.05;
  config.noise.short_probability = 0.1;
  config.noise.short_lambda = 0.3;
  config.noise.random_probability = 0.05;
  return config;
}

double NormalCdf(double x, double mean, double sigma) {
  return 0.5 * std::erfc(-(x - mean) / (sigma * std::sqrt(2.0)));
}

// The mixture's probability of a finite reading in [a, b) (m), a and b within the range limits.
double MixtureMass(const LidarNoiseConfig& n, double range_min, double range_max, double a,
                   double b) {
  const double p_hit = 1.0 - n.dropout_probability - n.short_probability - n.random_probability;
  const double hit = NormalCdf(b, kWall, n.sigma0) - NormalCdf(a, kWall, n.sigma0);
  const auto short_cdf = [&](double z) {
    z = std::clamp(z, range_min, kWall);
    return std::expm1(-n.short_lambda * (z - range_min)) /
           std::expm1(-n.short_lambda * (kWall - range_min));
  };
  const double random = (b - a) / (range_max - range_min);
  return p_hit * hit + n.short_probability * (short_cdf(b) - short_cdf(a)) +
         n.random_probability * random;
}

// Bin edges: coarse over the short and random parts, fine across the wall's Gaussian.
std::vector<double> BinEdges() {
  std::vector<double> edges;
  for (double z = 0.05; z < 7.8 - 1e-9; z += 0.25) edges.push_back(z);
  for (double z = 7.8; z < 8.2 - 1e-9; z += 0.025) edges.push_back(z);
  for (double z = 8.2; z < 30.0 - 1e-9; z += 2.2) edges.push_back(z);
  edges.push_back(30.0);
  return edges;
}

// The chi-square critical value for `df` degrees of freedom at p = 0.001 (Wilson-Hilferty).
double ChiSquareCritical(int df) {
  const double k = 2.0 / (9.0 * df);
  return df * std::pow(1.0 - k + 3.09 * std::sqrt(k), 3.0);
}

TEST(LidarMixture, ReadingsAgainstAKnownWallFollowTheFourPartMixture) {
  const LidarConfig config = MixtureLidar();
  StaticGeometry room;
  room.AddCircle({{0.0, 0.0}, kWall});
  const Lidar lidar(config, room);
  const std::vector<double> edges = BinEdges();
  const std::size_t bins = edges.size() - 1;
  for (const std::uint64_t seed : {21u, 22u, 23u}) {
    core::Rng rng(seed);
    std::vector<double> counts(bins + 1, 0.0);  // the last: no return (+inf)
    double n = 0.0;
    for (int k = 0; k < 100; ++k) {
      const LidarReading r = lidar.Scan(core::Pose2(), {}, 0.0, rng);
      for (const float reading : r.scan.ranges) {
        n += 1.0;
        if (std::isinf(reading) && reading > 0.0) {
          counts[bins] += 1.0;
          continue;
        }
        ASSERT_TRUE(std::isfinite(reading));
        const auto it = std::upper_bound(edges.begin(), edges.end(), double{reading});
        ASSERT_TRUE(it != edges.begin() && it != edges.end()) << reading;
        counts[static_cast<std::size_t>(it - edges.begin()) - 1] += 1.0;
      }
    }
    double chi2 = 0.0;
    for (std::size_t b = 0; b <= bins; ++b) {
      const double p = b < bins ? MixtureMass(config.noise, config.range_min, config.range_max,
                                              edges[b], edges[b + 1])
                                : config.noise.dropout_probability;
      const double expected = n * p;
      ASSERT_GT(expected, 5.0) << "bin " << b;
      chi2 += (counts[b] - expected) * (counts[b] - expected) / expected;
    }
    EXPECT_LT(chi2, ChiSquareCritical(static_cast<int>(bins))) << "seed " << seed;
  }
}

TEST(LidarMixture, ShortReturnsWithoutLambdaStayUniform) {
  LidarConfig config = MixtureLidar();
  config.noise = {};
  config.noise.sigma0 = 0.0;
  config.noise.sigma1 = 0.0;
  config.noise.dropout_probability = 0.0;
  config.noise.short_probability = 1.0;
  StaticGeometry room;
  room.AddCircle({{0.0, 0.0}, kWall});
  const Lidar lidar(config, room);
  core::Rng rng(5);
  double sum = 0.0, n = 0.0;
  for (int k = 0; k < 20; ++k) {
    for (const float reading : lidar.Scan(core::Pose2(), {}, 0.0, rng).scan.ranges) {
      sum += reading;
      n += 1.0;
    }
  }
  // Uniform in [0.05, 8): mean 4.025, standard error 2.3 / sqrt(21620) = 0.016.
  EXPECT_NEAR(sum / n, 4.025, 0.08);
}

TEST(LidarMixture, ValidateNamesTheNewKeys) {
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.noise.short_lambda = -1.0; }),
            "noise.short_lambda");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.noise.random_probability = 2.0; }),
            "noise.random_probability");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) {
              c.noise.dropout_probability = 0.4;
              c.noise.short_probability = 0.4;
              c.noise.random_probability = 0.4;
            }),
            "noise.random_probability");
}

}  // namespace
}  // namespace retrace::sim
