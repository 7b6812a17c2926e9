#include "bench/metrics/statistics.hpp"

#include <cmath>
#include <limits>

#include "core/check.hpp"

namespace retrace::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<double> Finite(const std::vector<double>& values) {
  std::vector<double> out;
  for (double v : values) {
    if (std::isfinite(v)) out.push_back(v);
  }
  return out;
}

// The continued fraction of I_x(a, b) by the modified Lentz method (Numerical Recipes, 3rd ed.,
// §6.4, eq. 6.4.5); converges quickly for x < (a + 1) / (a + b + 2).
double BetaContinuedFraction(double a, double b, double x) {
  constexpr int kMaxIterations = 1000;
  constexpr double kEpsilon = 1e-15;
  constexpr double kTiny = 1e-300;
  auto guard = [](double v) { return std::abs(v) < kTiny ? kTiny : v; };
  const double qab = a + b;
  const double qap = a + 1.0;
  const double qam = a - 1.0;
  double c = 1.0;
  double d = 1.0 / guard(1.0 - qab * x / qap);
  double h = d;
  for (int m = 1; m <= kMaxIterations; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((qam + m2) * (a + m2));  // even step
    d = 1.0 / guard(1.0 + aa * d);
    c = guard(1.0 + aa / c);
    h *= d * c;
    aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));  // odd step
    d = 1.0 / guard(1.0 + aa * d);
    c = guard(1.0 + aa / c);
    const double step = d * c;
    h *= step;
    if (std::abs(step - 1.0) < kEpsilon) break;
  }
  return h;
}

}  // namespace

double Mean(const std::vector<double>& values) {
  const std::vector<double> v = Finite(values);
  if (v.empty()) return kNaN;
  double sum = 0.0;
  for (double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

double SampleStandardDeviation(const std::vector<double>& values) {
  const std::vector<double> v = Finite(values);
  if (v.size() < 2) return kNaN;
  const double mean = Mean(v);
  double sum = 0.0;
  for (double x : v) sum += (x - mean) * (x - mean);  // two passes: no cancellation
  return std::sqrt(sum / static_cast<double>(v.size() - 1));
}

double RegularizedIncompleteBeta(double a, double b, double x) {
  RETRACE_CHECK(a > 0.0 && b > 0.0 && x >= 0.0 && x <= 1.0);
  if (x == 0.0 || x == 1.0) return x;
  // The prefactor x^a (1 - x)^b / (a B(a, b)), in logs against overflow.
  const double log_front =
      std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  const double front = std::exp(log_front);
  // The symmetry I_x(a, b) = 1 - I_{1-x}(b, a) keeps the continued fraction where it converges.
  if (x < (a + 1.0) / (a + b + 2.0)) return front * BetaContinuedFraction(a, b, x) / a;
  return 1.0 - front * BetaContinuedFraction(b, a, 1.0 - x) / b;
}

double StudentTCdf(double t, double dof) {
  RETRACE_CHECK(dof > 0.0);
  if (std::isnan(t)) return kNaN;
  if (std::isinf(t)) return t > 0.0 ? 1.0 : 0.0;
  // P(|T| > |t|) = I_{dof / (dof + t^2)}(dof / 2, 1 / 2).
  const double tail = 0.5 * RegularizedIncompleteBeta(0.5 * dof, 0.5, dof / (dof + t * t));
  return t > 0.0 ? 1.0 - tail : tail;
}

double StudentTQuantile(double p, double dof) {
  RETRACE_CHECK(p > 0.0 && p < 1.0 && dof > 0.0);
  if (p == 0.5) return 0.0;
  // Solve 0.5 I_x(dof / 2, 1 / 2) = min(p, 1 - p) for x = dof / (dof + t^2) by bisection:
  // I_x is increasing in x, and x in [0, 1] resolves small one-sided tails without the
  // cancellation of 1 - CDF.
  const double tail = p < 0.5 ? p : 1.0 - p;
  double lo = 0.0;
  double hi = 1.0;
  for (int i = 0; i < 2000 && hi - lo > 0.0; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;  // the interval is down to adjacent doubles
    if (0.5 * RegularizedIncompleteBeta(0.5 * dof, 0.5, mid) < tail) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  const double x = 0.5 * (lo + hi);
  const double t = std::sqrt(dof * (1.0 - x) / x);
  return p < 0.5 ? -t : t;
}

bool MeanInterval::ExcludesZero() const {
  return n >= 2 && std::isfinite(lower) && std::isfinite(upper) && (lower > 0.0 || upper < 0.0);
}

MeanInterval MeanConfidenceInterval(const std::vector<double>& values, double confidence) {
  RETRACE_CHECK(confidence > 0.0 && confidence < 1.0);
  const std::vector<double> v = Finite(values);
  MeanInterval out;
  out.n = static_cast<int>(v.size());
  out.mean = Mean(v);
  out.sd = SampleStandardDeviation(v);
  out.lower = kNaN;
  out.upper = kNaN;
  if (out.n >= 2) {
    const double half =
        StudentTQuantile(0.5 * (1.0 + confidence), out.n - 1) * out.sd / std::sqrt(out.n);
    out.lower = out.mean - half;
    out.upper = out.mean + half;
  }
  return out;
}

PairedComparison ComparePaired(const std::vector<double>& x, const std::vector<double>& reference,
                               double confidence) {
  RETRACE_CHECK(x.size() == reference.size());
  std::vector<double> diffs;
  std::vector<double> xs;
  std::vector<double> refs;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(reference[i])) continue;
    diffs.push_back(x[i] - reference[i]);
    xs.push_back(x[i]);
    refs.push_back(reference[i]);
  }
  PairedComparison out;
  out.difference = MeanConfidenceInterval(diffs, confidence);
  const double ref_mean = Mean(refs);
  out.ratio_of_means = std::isfinite(ref_mean) && ref_mean != 0.0 ? Mean(xs) / ref_mean : kNaN;
  out.significant = out.difference.ExcludesZero();
  return out;
}

}  // namespace retrace::bench
