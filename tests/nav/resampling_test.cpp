#include "nav/resampling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/rng.hpp"

namespace retrace::nav {
namespace {

TEST(Resampling, NormalizesHugeNegativeLogWeightsWithoutUnderflow) {
  const std::vector<double> log_w = {-10000.0, -10001.0, -10002.0, -1e308};
  std::vector<double> w(log_w.size());
  const double log_sum = NormalizeLogWeights(log_w, w);
  const double z = 1.0 + std::exp(-1.0) + std::exp(-2.0);
  EXPECT_NEAR(w[0], 1.0 / z, 1e-12);
  EXPECT_NEAR(w[1], std::exp(-1.0) / z, 1e-12);
  EXPECT_EQ(w[3], 0.0);
  EXPECT_NEAR(log_sum, -10000.0 + std::log(z), 1e-9);
  // All -inf: uniform.
  const std::vector<double> none(3, -std::numeric_limits<double>::infinity());
  std::vector<double> u(3);
  NormalizeLogWeights(none, u);
  for (const double x : u) EXPECT_DOUBLE_EQ(x, 1.0 / 3.0);
}

TEST(Resampling, EffectiveSampleSize) {
  EXPECT_DOUBLE_EQ(EffectiveSampleSize(std::vector<double>(10, 0.1)), 10.0);
  EXPECT_DOUBLE_EQ(EffectiveSampleSize(std::vector<double>{1.0, 0.0, 0.0}), 1.0);
  EXPECT_NEAR(EffectiveSampleSize(std::vector<double>{0.5, 0.25, 0.25}), 1.0 / 0.375, 1e-12);
}

TEST(Resampling, LowVarianceCopiesEachParticleFloorOrCeilOfNTimesItsWeight) {
  core::Rng rng(1);
  for (int trial = 0; trial < 50; ++trial) {
    const std::size_t n = 1 + rng.UniformIndex(300);
    std::vector<double> w(n);
    double sum = 0.0;
    for (auto& x : w) sum += (x = rng.Bernoulli(0.2) ? 0.0 : rng.Uniform() * rng.Uniform());
    if (sum == 0.0) w[0] = sum = 1.0;
    for (auto& x : w) x /= sum;
    const std::vector<std::size_t> idx = LowVarianceResample(w, n, rng);
    ASSERT_EQ(idx.size(), n);
    std::vector<int> copies(n, 0);
    for (std::size_t m = 0; m < n; ++m) {
      if (m > 0) {
        EXPECT_LE(idx[m - 1], idx[m]);
      }
      ++copies[idx[m]];
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double e = static_cast<double>(n) * w[i];
      EXPECT_GE(copies[i], std::floor(e) - 1e-9 > 0 ? std::floor(e - 1e-9) : 0) << i;
      EXPECT_LE(copies[i], std::ceil(e + 1e-9)) << i;
      if (w[i] == 0.0) {
        EXPECT_EQ(copies[i], 0);
      }
    }
  }
}

TEST(Resampling, LowVariancePreservesTheWeightDistributionOverSeeds) {
  // Expected copies N·w_i; chi-square of the summed counts over 400 seeds against the
  // expectation, 20 particles (19 degrees of freedom).
  const std::vector<double> w = {0.30, 0.01, 0.02, 0.005, 0.10, 0.0,  0.07, 0.033, 0.041, 0.05,
                                 0.09, 0.011, 0.06, 0.02,  0.03, 0.04, 0.05, 0.03,  0.02,  0.03};
  double total = 0.0;
  for (const double x : w) total += x;
  std::vector<double> p(w.size());
  for (std::size_t i = 0; i < w.size(); ++i) p[i] = w[i] / total;
  const std::size_t n = 37;  // not a multiple of anything
  const int seeds = 400;
  std::vector<double> counts(w.size(), 0.0);
  for (int s = 0; s < seeds; ++s) {
    core::Rng rng(static_cast<std::uint64_t>(s));
    for (const std::size_t i : LowVarianceResample(p, n, rng)) counts[i] += 1.0;
  }
  double chi2 = 0.0;
  int dof = -1;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double e = p[i] * n * seeds;
    if (e == 0.0) {
      EXPECT_EQ(counts[i], 0.0);
      continue;
    }
    chi2 += (counts[i] - e) * (counts[i] - e) / e;
    ++dof;
  }
  std::printf("[ report ] low-variance resampling: chi-square %.2f with %d degrees of freedom\n",
              chi2, dof);
  // Systematic resampling is far less variable than multinomial: chi-square well below the
  // 99.9 % quantile of the multinomial case (43.8 for 18 dof).
  EXPECT_LT(chi2, 43.8);
}

}  // namespace
}  // namespace retrace::nav
