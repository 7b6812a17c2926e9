#include "nav/resampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.hpp"

namespace retrace::nav {

double NormalizeLogWeights(std::span<const double> log_weights, std::span<double> weights) {
  RETRACE_CHECK(weights.size() == log_weights.size());
  if (log_weights.empty()) return -std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  for (const double l : log_weights) {
    RETRACE_CHECK(!std::isnan(l) && l != std::numeric_limits<double>::infinity());
    max = std::max(max, l);
  }
  if (max == -std::numeric_limits<double>::infinity()) {
    std::fill(weights.begin(), weights.end(), 1.0 / static_cast<double>(weights.size()));
    return max;
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < log_weights.size(); ++i) {
    weights[i] = std::exp(log_weights[i] - max);
    sum += weights[i];
  }
  const double inv = 1.0 / sum;  // sum >= 1: the maximum contributes exp(0)
  for (double& w : weights) w *= inv;
  return max + std::log(sum);
}

double EffectiveSampleSize(std::span<const double> weights) {
  double sum_sq = 0.0;
  for (const double w : weights) sum_sq += w * w;
  return sum_sq > 0.0 ? 1.0 / sum_sq : 0.0;
}

std::vector<std::size_t> LowVarianceResample(std::span<const double> weights, std::size_t n,
                                             core::Rng& rng) {
  return LowVarianceResampleWithOffset(weights, n, rng.Uniform());
}

std::vector<std::size_t> LowVarianceResampleWithOffset(std::span<const double> weights,
                                                       std::size_t n, double u) {
  RETRACE_CHECK(!weights.empty() || n == 0);
  RETRACE_CHECK(u >= 0.0 && u < 1.0);
  std::vector<std::size_t> out;
  out.reserve(n);
  if (n == 0) return out;
  const double step = 1.0 / static_cast<double>(n);
  std::size_t i = 0;
  double cumulative = weights[0];
  // Rounding can leave the comb's last teeth just beyond the cumulative sum: they go to the
  // last particle with a positive weight, never to one of weight 0.
  std::size_t last = weights.size() - 1;
  while (last > 0 && !(weights[last] > 0.0)) --last;
  double total = 0.0;
  for (const double w : weights) {
    RETRACE_CHECK(w >= 0.0);
    total += w;
  }
  RETRACE_CHECK(std::abs(total - 1.0) < 1e-6);
  for (std::size_t m = 0; m < n; ++m) {
    // Tooth m of the comb; computed, not accumulated, so rounding does not drift over n teeth.
    const double tooth = (static_cast<double>(m) + u) * step;
    while (tooth >= cumulative && i < last) {
      ++i;
      cumulative += weights[i];
    }
    out.push_back(i);
  }
  return out;
}

}  // namespace retrace::nav
