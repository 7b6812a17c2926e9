#pragma once
// Particle weight bookkeeping: log-weight normalisation, effective sample size and low-variance
// (systematic) resampling in O(N).

#include <cstddef>
#include <span>
#include <vector>

#include "core/rng.hpp"

namespace retrace::nav {

/// Turns log-weights into normalised weights (sum 1) by subtracting the maximum before
/// exponentiating, so no sum underflows. Returns log Σ exp(log_weights) (the log of the total
/// unnormalised weight). weights must have the size of log_weights (checked); an empty input
/// returns -inf. Non-finite log-weights (checked: no NaN, no +inf) of -inf get weight 0; if all
/// are -inf the weights become uniform.
double NormalizeLogWeights(std::span<const double> log_weights, std::span<double> weights);

/// Kish's effective sample size 1 / Σ w_i² of normalised weights (between 1 and N).
double EffectiveSampleSize(std::span<const double> weights);

/// Low-variance (systematic) resampling (Probabilistic Robotics Table 4.4): n draws with one
/// random offset u0 in [0, 1/n); particle i is copied floor or ceil of n·w_i times. weights must
/// be normalised (sum 1 within rounding; checked loosely) and non-negative. Returns the indices
/// of the drawn particles in increasing order. O(N + n).
std::vector<std::size_t> LowVarianceResample(std::span<const double> weights, std::size_t n,
                                             core::Rng& rng);
/// The same with a given offset u in [0, 1) (the comb's first tooth is at u / n).
std::vector<std::size_t> LowVarianceResampleWithOffset(std::span<const double> weights,
                                                       std::size_t n, double u);

}  // namespace retrace::nav
