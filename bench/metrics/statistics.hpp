#pragma once
// Small-sample statistics for comparisons over seeds: mean, sample standard deviation, the
// Student t distribution and confidence intervals of a mean and of a paired difference.
//
// Definitions (n = the number of finite values; non-finite values are left out):
//   mean = sum x_i / n;  sd = sqrt(sum (x_i - mean)^2 / (n - 1))  (NaN for n < 2)
//   CI of the mean at confidence c: mean -+ t_{(1 + c) / 2, n - 1} sd / sqrt(n)  (NaN for n < 2)
//   paired difference of x against a reference r: d_i = x_i - r_i over the pairs where both are
//   finite, with the CI above of mean(d); significant when that CI excludes 0; ratio of means =
//   mean(x) / mean(r) over the same pairs (NaN when mean(r) is 0).
// The t quantile is computed, not tabulated: the t CDF through the regularized incomplete beta
// function (continued fraction), inverted by bisection to double precision.

#include <limits>
#include <vector>

namespace retrace::bench {

/// Mean of the finite values; NaN when there are none.
double Mean(const std::vector<double>& values);

/// Sample standard deviation (n - 1 denominator) of the finite values; NaN when fewer than 2.
double SampleStandardDeviation(const std::vector<double>& values);

/// Regularized incomplete beta function I_x(a, b) for a, b > 0 and x in [0, 1].
double RegularizedIncompleteBeta(double a, double b, double x);

/// P(T <= t) for Student's t distribution with `dof` > 0 degrees of freedom.
double StudentTCdf(double t, double dof);

/// The p-quantile of Student's t distribution: the t with StudentTCdf(t, dof) = p, for p in
/// (0, 1) and dof > 0 (aborts otherwise: callers pass constants and counts).
double StudentTQuantile(double p, double dof);

/// A mean with its confidence interval.
struct MeanInterval {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  int n = 0;            ///< finite values used
  double mean = kNaN;   ///< NaN when n = 0
  double sd = kNaN;     ///< NaN when n < 2
  double lower = kNaN;  ///< NaN when n < 2
  double upper = kNaN;  ///< NaN when n < 2
  /// True when the interval exists and does not contain 0.
  bool ExcludesZero() const;
};

/// The mean of the finite values and its Student t confidence interval (confidence in (0, 1)).
MeanInterval MeanConfidenceInterval(const std::vector<double>& values, double confidence = 0.95);

/// `x` against a reference measured on the same seeds (paired by index).
struct PairedComparison {
  MeanInterval difference;  ///< of x_i - reference_i
  /// mean(x) / mean(reference) over the pairs; NaN when undefined
  double ratio_of_means = MeanInterval::kNaN;
  bool significant = false;  ///< the difference's interval excludes 0
};

/// The paired difference x - reference over the indices where both are finite. x and
/// reference must have the same size (aborts otherwise).
PairedComparison ComparePaired(const std::vector<double>& x, const std::vector<double>& reference,
                               double confidence = 0.95);

}  // namespace retrace::bench
