// The beam model's EM (Probabilistic Robotics Table 6.2) on synthetic beams drawn from a known
// mixture: it recovers the weights, σ, λ and the hit offset within their sampling error, for a
// fixed list of seeds; and it reports when it stops at its iteration cap.

#include "nav/beam_mixture_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/rng.hpp"

namespace retrace::nav {
namespace {

constexpr double kRangeMin = 0.05;
constexpr double kRangeMax = 30.0;

BeamMixture TrueMixture() {
  BeamMixture m;
  m.z_hit = 0.75;
  m.z_short = 0.12;
  m.z_max = 0.08;
  m.z_rand = 0.05;
  m.sigma_hit = 0.04;
  m.lambda_short = 0.4;
  m.hit_offset = 0.06;
  return m;
}

// n beams with expected ranges uniform in [1, 12] m, readings drawn from m as the simulated
// LiDAR draws them (sim/lidar.cpp).
std::vector<BeamSample> Draw(const BeamMixture& m, int n, core::Rng rng) {
  std::vector<BeamSample> out;
  for (int i = 0; i < n; ++i) {
    BeamSample s;
    s.z_star = rng.Uniform(1.0, 12.0);
    const double u = rng.Uniform();
    if (u < m.z_max) {
      s.z = std::numeric_limits<double>::infinity();
    } else if (u < m.z_max + m.z_short) {
      const double length = s.z_star - kRangeMin;
      const double v = rng.Uniform();
      s.z = m.lambda_short == 0.0
                ? kRangeMin + v * length
                : kRangeMin - std::log1p(v * std::expm1(-m.lambda_short * length)) / m.lambda_short;
    } else if (u < m.z_max + m.z_short + m.z_rand) {
      s.z = rng.Uniform(kRangeMin, kRangeMax);
    } else {
      s.z = s.z_star + m.hit_offset + m.sigma_hit * rng.Normal();
    }
    out.push_back(s);
  }
  return out;
}

TEST(BeamMixtureFit, RecoversTheParametersOfAKnownMixture) {
  const BeamMixture truth = TrueMixture();
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const std::vector<BeamSample> samples = Draw(truth, 40000, core::Rng(seed));
    const BeamFitResult fit = FitBeamMixture(samples, kRangeMin, kRangeMax);
    ASSERT_TRUE(fit.converged) << "seed " << seed << ": " << fit.iterations << " iterations";
    const BeamMixture& m = fit.mixture;
    // Binomial standard errors at n = 40000: 0.002 (hit), 0.0016 (short), 0.0014, 0.0011.
    EXPECT_NEAR(m.z_hit, truth.z_hit, 0.01) << seed;
    EXPECT_NEAR(m.z_short, truth.z_short, 0.01) << seed;
    EXPECT_NEAR(m.z_max, truth.z_max, 0.006) << seed;
    EXPECT_NEAR(m.z_rand, truth.z_rand, 0.008) << seed;
    EXPECT_NEAR(m.sigma_hit / truth.sigma_hit, 1.0, 0.03) << seed;
    EXPECT_NEAR(m.lambda_short / truth.lambda_short, 1.0, 0.12) << seed;
    EXPECT_NEAR(m.hit_offset, truth.hit_offset, 0.002) << seed;
    EXPECT_NEAR(m.z_hit + m.z_short + m.z_max + m.z_rand, 1.0, 1e-9);
    EXPECT_EQ(fit.beams, samples.size());
  }
}

TEST(BeamMixtureFit, UniformShortReturnsGiveASmallLambda) {
  BeamMixture truth = TrueMixture();
  truth.lambda_short = 0.0;
  for (const std::uint64_t seed : {4u, 5u}) {
    const BeamFitResult fit =
        FitBeamMixture(Draw(truth, 40000, core::Rng(seed)), kRangeMin, kRangeMax);
    ASSERT_TRUE(fit.converged);
    EXPECT_LT(fit.mixture.lambda_short, 0.03) << seed;
    EXPECT_NEAR(fit.mixture.z_short, truth.z_short, 0.015) << seed;
  }
}

TEST(BeamMixtureFit, ReportsStoppingAtTheIterationCap) {
  BeamFitOptions options;
  options.max_iterations = 2;
  const BeamFitResult fit =
      FitBeamMixture(Draw(TrueMixture(), 2000, core::Rng(7)), kRangeMin, kRangeMax, options);
  EXPECT_FALSE(fit.converged);
  EXPECT_EQ(fit.iterations, 2);
  EXPECT_GT(fit.last_change, options.tolerance);
}

TEST(BeamMixtureFit, ContinuousDensityIntegratesToOneMinusTheMaxWeight) {
  const BeamMixture m = TrueMixture();
  for (const double z_star : {0.5, 4.0, 29.9}) {
    double integral = 0.0;
    const double dz = 1e-4;
    for (double z = kRangeMin + dz / 2; z < kRangeMax; z += dz)
      integral += BeamMixtureDensity(m, z, z_star, kRangeMin, kRangeMax) * dz;
    EXPECT_NEAR(integral, 1.0 - m.z_max, 2e-3) << z_star;
  }
}

}  // namespace
}  // namespace retrace::nav
