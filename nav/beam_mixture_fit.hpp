#pragma once
// Maximum-likelihood fit of the beam model's intrinsic parameters (Probabilistic Robotics Table
// 6.2, learn_intrinsic_parameters) to measured ranges z and their expected ranges z*: EM over
// the four parts of the mixture, hit, short, max and random. A pure kernel: no map, no log.
//
// The mixture is the one the simulated LiDAR draws (docs/METHOD.md), on the sensor's valid
// interval [range_min, range_max]:
//
//   p_hit   = N(z; z* + b, σ²) / (Φ((range_max − z* − b)/σ) − Φ((range_min − z* − b)/σ))
//   p_short = λ exp(−λ (z − range_min)) / (1 − exp(−λ (z* − range_min)))   range_min ≤ z ≤ z*
//             (1 / (z* − range_min) at λ = 0)
//   p_max   = a no-return reading (z ≥ range_max or +inf): a point mass
//   p_rand  = 1 / (range_max − range_min)
//
// E-step: the responsibilities e_hit, e_short, e_max, e_rand of every beam (a no-return beam is
// all max; a finite one is never max). M-step: each weight is its mean responsibility; b =
// Σ e_hit (z − z*) / Σ e_hit and σ² = Σ e_hit (z − z* − b)² / Σ e_hit; λ the maximum of Σ e_short
// log p_short, which solves Σ e_short · mean_λ(z* − range_min) = Σ e_short (z − range_min) with
// mean_λ(L) = 1/λ − L / (exp(λ L) − 1) the mean of the exponential truncated at L (Table 6.2's λ =
// Σ e_short / Σ e_short z is its limit for L → ∞); λ is kept >= 0 (0: short returns uniform).

#include <cstddef>
#include <span>

namespace retrace::nav {

/// One beam: the measured range z (m; >= range_max or +inf for no return) and the expected
/// range z* (m) that the map predicts, range_min < z* < range_max.
struct BeamSample {
  double z = 0.0;
  double z_star = 0.0;
};

/// The mixture's weights (summing to 1) and its hit and short parameters.
struct BeamMixture {
  double z_hit = 0.7;
  double z_short = 0.1;
  double z_max = 0.1;
  double z_rand = 0.1;
  double sigma_hit = 0.1;     ///< m
  double lambda_short = 0.1;  ///< 1/m
  double hit_offset = 0.0;    ///< m, b: the hit part's mean is z* + b
};

struct BeamFitOptions {
  int max_iterations = 1000;
  /// Converged when no weight moves by more than this, nor σ, λ and b by more than this relative
  /// to their value (λ: to max(λ, 0.01 1/m); b: to σ), in one iteration.
  double tolerance = 1e-6;
  BeamMixture initial;  ///< where EM starts
};

struct BeamFitResult {
  BeamMixture mixture;           ///< after the last iteration
  int iterations = 0;            ///< EM iterations run
  bool converged = false;        ///< false: stopped at max_iterations
  double last_change = 0.0;      ///< the largest (relative) parameter change of the last iteration
  double log_likelihood = 0.0;   ///< Σ log p (densities 1/m, the max part as a probability)
  std::size_t beams = 0;         ///< samples used
  std::size_t max_readings = 0;  ///< of them, no returns
};

/// Fits the mixture to `samples` (at least one; every z >= range_min, checked) by EM.
BeamFitResult FitBeamMixture(std::span<const BeamSample> samples, double range_min,
                             double range_max, const BeamFitOptions& options = {});

/// The continuous part of the mixture at a finite reading z (1/m): z_hit p_hit + z_short p_short
/// + z_rand p_rand, p_hit centred on z* + hit_offset (0 outside [range_min, range_max)).
double BeamMixtureDensity(const BeamMixture& m, double z, double z_star, double range_min,
                          double range_max);

}  // namespace retrace::nav
