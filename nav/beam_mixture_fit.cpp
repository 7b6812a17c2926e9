#include "nav/beam_mixture_fit.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/check.hpp"

namespace retrace::nav {

namespace {

constexpr double kSqrt2 = 1.4142135623730951;
constexpr double kInvSqrt2Pi = 0.3989422804014327;
constexpr double kMinSigma = 1e-4;  // m: a floor against a collapsing Gaussian

struct Responsibilities {
  double hit = 0.0, short_part = 0.0, max = 0.0, rand = 0.0;
};

double NormalCdf(double x) { return 0.5 * std::erfc(-x / kSqrt2); }

double HitDensity(double sigma, double z, double z_star, double range_min, double range_max) {
  // z_star here is the hit part's mean, z* + b.
  const double norm =
      NormalCdf((range_max - z_star) / sigma) - NormalCdf((range_min - z_star) / sigma);
  const double u = (z - z_star) / sigma;
  return norm > 0.0 ? kInvSqrt2Pi / sigma * std::exp(-0.5 * u * u) / norm : 0.0;
}

double ShortDensity(double lambda, double z, double z_star, double range_min) {
  const double length = z_star - range_min;
  if (!(z <= z_star) || !(length > 0.0)) return 0.0;
  if (lambda * length < 1e-9) return 1.0 / length;
  return lambda * std::exp(-lambda * (z - range_min)) / -std::expm1(-lambda * length);
}

// The mean of an exponential of rate lambda truncated to [0, length], and its derivative with
// respect to lambda (series for small lambda * length, the untruncated limit for large).
double TruncatedExpMean(double lambda, double length, double* derivative) {
  const double x = lambda * length;
  if (x < 1e-4) {
    *derivative = -length * length / 12.0;
    return length / 2.0 - lambda * length * length / 12.0;
  }
  if (x > 700.0) {
    *derivative = -1.0 / (lambda * lambda);
    return 1.0 / lambda;
  }
  const double em1 = std::expm1(x);
  *derivative = -1.0 / (lambda * lambda) + length * length * (em1 + 1.0) / (em1 * em1);
  return 1.0 / lambda - length / em1;
}

// The λ that maximises Σ e_short log p_short: Σ e_i mean_λ(L_i) = Σ e_i (z_i − range_min),
// by Newton's method kept inside a shrinking bracket; 0 when even λ = 0 gives too small a mean.
double SolveLambda(std::span<const BeamSample> samples, std::span<const double> e_short,
                   double range_min, double lambda) {
  double target = 0.0, at_zero = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (e_short[i] == 0.0) continue;
    target += e_short[i] * (samples[i].z - range_min);
    at_zero += e_short[i] * (samples[i].z_star - range_min) / 2.0;
  }
  if (!(target < at_zero)) return 0.0;
  double lo = 0.0, hi = std::max(1.0, 2.0 * lambda);
  const auto g = [&](double l, double* dg) {
    double sum = 0.0, dsum = 0.0, d = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (e_short[i] == 0.0) continue;
      sum += e_short[i] * TruncatedExpMean(l, samples[i].z_star - range_min, &d);
      dsum += e_short[i] * d;
    }
    *dg = dsum;
    return sum - target;
  };
  double dg = 0.0;
  while (g(hi, &dg) > 0.0 && hi < 1e9) hi *= 4.0;
  double l = std::clamp(lambda, lo, hi);
  for (int step = 0; step < 100; ++step) {
    const double v = g(l, &dg);
    (v > 0.0 ? lo : hi) = l;
    double next = dg < 0.0 ? l - v / dg : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - l) <= 1e-12 * (1.0 + l)) return next;
    l = next;
  }
  return l;
}

// E-step for one beam under mixture m; adds log p to *log_likelihood.
Responsibilities EStep(const BeamMixture& m, const BeamSample& s, double range_min,
                       double range_max, double* log_likelihood) {
  Responsibilities e;
  if (s.z >= range_max) {
    e.max = 1.0;
    *log_likelihood += std::log(std::max(m.z_max, 1e-300));
    return e;
  }
  e.hit = m.z_hit * HitDensity(m.sigma_hit, s.z, s.z_star + m.hit_offset, range_min, range_max);
  e.short_part = m.z_short * ShortDensity(m.lambda_short, s.z, s.z_star, range_min);
  e.rand = m.z_rand / (range_max - range_min);
  const double total = e.hit + e.short_part + e.rand;
  if (!(total > 0.0)) {
    *log_likelihood += std::log(1e-300);
    return {0.0, 0.0, 0.0, 1.0};
  }
  *log_likelihood += std::log(total);
  return {e.hit / total, e.short_part / total, 0.0, e.rand / total};
}

// The largest change from a to b: weights absolute, σ and λ relative.
double Change(const BeamMixture& a, const BeamMixture& b) {
  double c = std::max({std::abs(a.z_hit - b.z_hit), std::abs(a.z_short - b.z_short),
                       std::abs(a.z_max - b.z_max), std::abs(a.z_rand - b.z_rand)});
  c = std::max(c, std::abs(a.sigma_hit - b.sigma_hit) / b.sigma_hit);
  c = std::max(c, std::abs(a.hit_offset - b.hit_offset) / b.sigma_hit);
  return std::max(c, std::abs(a.lambda_short - b.lambda_short) / std::max(b.lambda_short, 0.01));
}

// One EM iteration: the E-step over every beam, then the M-step.
BeamMixture Iterate(const BeamMixture& m, std::span<const BeamSample> samples, double range_min,
                    double range_max, std::vector<double>* e_short, double* log_likelihood) {
  Responsibilities sum;
  double hit_d = 0.0, hit_sq = 0.0;  // Σ e_hit d, Σ e_hit d², d = z − z* − b
  *log_likelihood = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Responsibilities e = EStep(m, samples[i], range_min, range_max, log_likelihood);
    sum.hit += e.hit;
    sum.short_part += e.short_part;
    sum.max += e.max;
    sum.rand += e.rand;
    const double d = samples[i].z - samples[i].z_star - m.hit_offset;
    if (e.hit > 0.0) {
      hit_d += e.hit * d;
      hit_sq += e.hit * d * d;
    }
    (*e_short)[i] = e.short_part;
  }
  const double n = static_cast<double>(samples.size());
  BeamMixture next = m;
  next.z_hit = sum.hit / n;
  next.z_short = sum.short_part / n;
  next.z_max = sum.max / n;
  next.z_rand = sum.rand / n;
  if (sum.hit > 0.0) {
    // Centred on the new mean: Σ e (d − δ)² = Σ e d² − δ Σ e d with δ = Σ e d / Σ e.
    const double shift = hit_d / sum.hit;
    next.hit_offset = m.hit_offset + shift;
    const double variance = std::max(hit_sq / sum.hit - shift * shift, 0.0);
    next.sigma_hit = std::max(std::sqrt(variance), kMinSigma);
  }
  if (sum.short_part > 0.0)
    next.lambda_short = SolveLambda(samples, *e_short, range_min, m.lambda_short);
  return next;
}

}  // namespace

BeamFitResult FitBeamMixture(std::span<const BeamSample> samples, double range_min,
                             double range_max, const BeamFitOptions& options) {
  RETRACE_CHECK(!samples.empty() && range_min >= 0.0 && range_max > range_min &&
                options.max_iterations >= 1);
  BeamFitResult result;
  result.beams = samples.size();
  for (const BeamSample& s : samples) {
    RETRACE_CHECK(s.z >= range_min && s.z_star > range_min && s.z_star < range_max);
    if (s.z >= range_max) ++result.max_readings;
  }
  std::vector<double> e_short(samples.size(), 0.0);
  BeamMixture m = options.initial;
  while (result.iterations < options.max_iterations) {
    const BeamMixture next =
        Iterate(m, samples, range_min, range_max, &e_short, &result.log_likelihood);
    ++result.iterations;
    result.last_change = Change(m, next);
    m = next;
    if (result.last_change <= options.tolerance) {
      result.converged = true;
      break;
    }
  }
  result.mixture = m;
  return result;
}

double BeamMixtureDensity(const BeamMixture& m, double z, double z_star, double range_min,
                          double range_max) {
  if (!(z >= range_min && z < range_max)) return 0.0;
  return m.z_hit * HitDensity(m.sigma_hit, z, z_star + m.hit_offset, range_min, range_max) +
         m.z_short * ShortDensity(m.lambda_short, z, z_star, range_min) +
         m.z_rand / (range_max - range_min);
}

}  // namespace retrace::nav
