#include "bench/metrics/statistics.hpp"
#include "tests/support/special_values.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace retrace::bench {
namespace {

using retrace::testing::kNaN;

TEST(Statistics, MeanAndSampleStandardDeviationLeaveOutNonFiniteValues) {
  EXPECT_DOUBLE_EQ(Mean({1.0, 2.0, kNaN, 6.0}), 3.0);
  // (1-3)^2 + (2-3)^2 + (6-3)^2 = 14, over n - 1 = 2.
  EXPECT_DOUBLE_EQ(SampleStandardDeviation({1.0, 2.0, kNaN, 6.0}), std::sqrt(7.0));
  EXPECT_TRUE(std::isnan(Mean({})));
  EXPECT_TRUE(std::isnan(SampleStandardDeviation({4.0})));
}

TEST(Statistics, IncompleteBetaMatchesClosedForms) {
  for (double x : {0.0, 0.1, 0.37, 0.5, 0.93, 1.0}) {
    EXPECT_NEAR(RegularizedIncompleteBeta(1.0, 1.0, x), x, 1e-14);          // uniform
    EXPECT_NEAR(RegularizedIncompleteBeta(3.0, 1.0, x), x * x * x, 1e-14);  // x^a
    EXPECT_NEAR(RegularizedIncompleteBeta(2.0, 2.0, x), x * x * (3.0 - 2.0 * x), 1e-14);
  }
}

TEST(Statistics, StudentTCdfMatchesClosedForms) {
  const double pi = std::acos(-1.0);
  // dof 1 is the Cauchy distribution; dof 2 has F(t) = 1/2 + t / (2 sqrt(2 + t^2)).
  EXPECT_NEAR(StudentTCdf(1.0, 1.0), 0.75, 1e-14);
  EXPECT_NEAR(StudentTCdf(2.0, 1.0), 0.5 + std::atan(2.0) / pi, 1e-14);
  EXPECT_NEAR(StudentTCdf(-3.0, 1.0), 0.5 + std::atan(-3.0) / pi, 1e-14);
  EXPECT_NEAR(StudentTCdf(1.0, 2.0), 0.5 + 1.0 / (2.0 * std::sqrt(3.0)), 1e-14);
  EXPECT_DOUBLE_EQ(StudentTCdf(0.0, 7.0), 0.5);
}

// Two-sided 95 % critical values t_{0.975, dof} and a few others, from standard tables
// (e.g. NIST/SEMATECH e-Handbook, Table 1.3.6.7.2), to the tables' 3 decimals and beyond.
TEST(Statistics, StudentTQuantilesMatchTables) {
  struct Case {
    double p;
    double dof;
    double t;
  };
  const Case cases[] = {
      {0.975, 1, 12.7062047362},  {0.975, 2, 4.30265272975},   {0.975, 3, 3.18244630528},
      {0.975, 5, 2.57058183661},  {0.975, 7, 2.36462425159},   {0.975, 10, 2.22813885196},
      {0.975, 30, 2.04227245630}, {0.975, 100, 1.98397151852}, {0.95, 3, 2.35336343480},
      {0.995, 4, 4.60409487142},  {0.99, 20, 2.52797700058},   {0.9995, 1, 636.619248768},
  };
  for (const Case& c : cases) {
    EXPECT_NEAR(StudentTQuantile(c.p, c.dof), c.t, 1e-8 * c.t) << "p " << c.p << " dof " << c.dof;
    EXPECT_NEAR(StudentTQuantile(1.0 - c.p, c.dof), -c.t, 1e-8 * c.t)
        << "lower tail, dof " << c.dof;
  }
  EXPECT_DOUBLE_EQ(StudentTQuantile(0.5, 4.0), 0.0);
  // Many degrees of freedom: the normal quantile 1.959964.
  EXPECT_NEAR(StudentTQuantile(0.975, 1e6), 1.959963985, 1e-5);
}

TEST(Statistics, StudentTQuantileInvertsTheCdf) {
  for (double dof : {1.0, 2.5, 6.0, 40.0}) {
    for (double p : {0.001, 0.05, 0.3, 0.6, 0.9, 0.999}) {
      EXPECT_NEAR(StudentTCdf(StudentTQuantile(p, dof), dof), p, 1e-12)
          << "p " << p << " dof " << dof;
    }
  }
}

TEST(Statistics, ConfidenceIntervalOfAKnownSample) {
  // 1..5: mean 3, sd sqrt(2.5), half-width t_{0.975,4} sd / sqrt(5) = 2.776445105 * 0.707106781.
  const MeanInterval ci = MeanConfidenceInterval({1.0, 2.0, 3.0, 4.0, 5.0});
  EXPECT_EQ(ci.n, 5);
  EXPECT_DOUBLE_EQ(ci.mean, 3.0);
  EXPECT_NEAR(ci.sd, 1.58113883008, 1e-10);
  EXPECT_NEAR(ci.lower, 1.03675684, 1e-7);
  EXPECT_NEAR(ci.upper, 4.96324316, 1e-7);
  EXPECT_TRUE(ci.ExcludesZero());
  // A 90 % interval is narrower: t_{0.95,4} = 2.131847.
  const MeanInterval ci90 = MeanConfidenceInterval({1.0, 2.0, 3.0, 4.0, 5.0}, 0.90);
  EXPECT_NEAR(ci90.upper - ci90.mean, 2.13184678 * std::sqrt(0.5), 1e-7);
}

TEST(Statistics, ConfidenceIntervalNeedsTwoValues) {
  const MeanInterval one = MeanConfidenceInterval({kNaN, 2.0});
  EXPECT_EQ(one.n, 1);
  EXPECT_DOUBLE_EQ(one.mean, 2.0);
  EXPECT_TRUE(std::isnan(one.lower));
  EXPECT_TRUE(std::isnan(one.upper));
  EXPECT_FALSE(one.ExcludesZero());
  const MeanInterval none = MeanConfidenceInterval({});
  EXPECT_EQ(none.n, 0);
  EXPECT_TRUE(std::isnan(none.mean));
}

TEST(Statistics, PairedDifferenceOfAKnownSample) {
  // d = 0.3, 0.4, -0.1, 0.9, 0.3: mean 0.36, sd sqrt(0.128), half-width 2.776445 * 0.16.
  const std::vector<double> x = {2.1, 3.4, 1.9, 5.0, 4.2};
  const std::vector<double> r = {1.8, 3.0, 2.0, 4.1, 3.9};
  const PairedComparison p = ComparePaired(x, r);
  EXPECT_EQ(p.difference.n, 5);
  EXPECT_NEAR(p.difference.mean, 0.36, 1e-12);
  EXPECT_NEAR(p.difference.sd, std::sqrt(0.128), 1e-12);
  EXPECT_NEAR(p.difference.lower, 0.36 - 0.444231217, 1e-8);
  EXPECT_NEAR(p.difference.upper, 0.36 + 0.444231217, 1e-8);
  EXPECT_FALSE(p.significant);
  EXPECT_NEAR(p.ratio_of_means, 3.32 / 2.96, 1e-12);
}

TEST(Statistics, PairingFindsADifferenceThatSeedToSeedSpreadHides) {
  // Seeds differ a lot from each other, but x is always 0.1 above the reference.
  const std::vector<double> r = {1.0, 5.0, 2.0, 8.0};
  const std::vector<double> x = {1.1, 5.12, 2.08, 8.1};
  const PairedComparison p = ComparePaired(x, r);
  EXPECT_TRUE(p.significant);
  EXPECT_GT(p.difference.lower, 0.0);
  // The modes' own intervals overlap widely.
  EXPECT_LT(MeanConfidenceInterval(x).lower, MeanConfidenceInterval(r).upper);
}

TEST(Statistics, PairedDifferenceUsesOnlyPairsWithBothValues) {
  const PairedComparison p = ComparePaired({1.0, kNaN, 3.0, 4.0}, {0.5, 2.0, kNaN, 3.0});
  EXPECT_EQ(p.difference.n, 2);
  EXPECT_DOUBLE_EQ(p.difference.mean, 0.75);
  EXPECT_DOUBLE_EQ(p.ratio_of_means, 2.5 / 1.75);
  // A zero reference mean has no ratio.
  EXPECT_TRUE(std::isnan(ComparePaired({1.0, 2.0}, {0.0, 0.0}).ratio_of_means));
  // Identical values: a zero-width interval at 0, not significant.
  EXPECT_FALSE(ComparePaired({1.0, 2.0}, {1.0, 2.0}).significant);
}

}  // namespace
}  // namespace retrace::bench
