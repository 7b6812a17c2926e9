#pragma once
// The beam model of Probabilistic Robotics Table 6.1 and the dynamic scan point test of Table
// 8.5 (paper eq. 7-9): a beam is "dynamic" (it hit something the map does not contain) when,
// summed over the particles, the short-reading term explains most of its probability.

#include <cstdint>
#include <span>
#include <vector>

namespace retrace::nav {

/// Mixture weights and parameters of the beam model (eq. 7-9).
///
///   p_beam(z | z*) = (z_hit p_hit + z_short p_short + z_max p_max + z_rand p_rand) / Σz
///
///   p_hit   = N(z; z*, σ²) / (Φ((z_max_range - z*)/σ) - Φ(-z*/σ))   on [0, range_max]
///   p_short = η λ exp(-λ z), η = 1 / (1 - exp(-λ z*))               for 0 <= z <= z*, else 0
///   p_max   = 1 if z >= range_max (a point mass), else 0
///   p_rand  = 1 / range_max                                          on [0, range_max)
///
/// The mixture weights are divided by their sum Σz so that the density integrates to 1 (the
/// defaults sum to 1.1); the dynamic-point ratio does not depend on that normalisation.
/// z* = 0 (the sensor inside an occupied cell) leaves no room for a short reading: p_short = 0.
///
/// The ratio of eq. (9) for a return well short of z* (p_hit ≈ 0) is s / (s + w_rand/range_max)
/// with s = w_short p_short ≈ w_short / z* for small λ z*: it exceeds χ = 0.9 only while
/// z* < z_short range_max / (9 z_rand). Defaults: the original's z_hit 0.9, z_short 0.1, z_max
/// 0.05 and λ_short 0.05 1/m (p_short nearly uniform over [0, z*]), but z_rand = 0.01 rather than
/// 0.05, which would stop rejecting pedestrians in front of anything farther than 6.7 m (30 m
/// sensor); truly random returns are rarer than that on a Hokuyo (about 0.2 %). σ_hit = 0.1 m:
/// z* is ray-cast exactly to the cell face, so σ covers the range noise (0.01-0.04 m) and the
/// particles' spread; a σ of 0.2 m let a wall 0.6 m behind a pedestrian "explain" its return as
/// a hit and cut recall from 95 % to 88 % in tests/nav/localizer_test.cpp.
struct BeamModelConfig {
  double z_hit = 0.9;
  double z_short = 0.1;
  double z_max = 0.05;
  double z_rand = 0.01;
  double sigma_hit = 0.1;      ///< m
  double lambda_short = 0.05;  ///< 1/m

  template <class V>
  void Reflect(V& v) {
    v("z_hit", z_hit);
    v("z_short", z_short);
    v("z_max", z_max);
    v("z_rand", z_rand);
    v("sigma_hit", sigma_hit);
    v("lambda_short", lambda_short);
  }
  /// Throws core::ConfigError naming the key (e.g. "lambda_short").
  void Validate() const;
};

/// The beam model for a sensor with maximum range range_max (m).
///
/// "No obstacle on the ray" (the grid ray caster returns kNoHit): the map says the beam should
/// reach the maximum range, so the expected range is z* = range_max. A finite reading z <
/// range_max then has p_hit ≈ 0 unless it is near range_max, p_short = η λ exp(-λ z) with
/// η = 1 / (1 - exp(-λ range_max)), so a return from something unmapped in open space counts
/// as short (dynamic) evidence instead of being dropped.
class BeamModel {
 public:
  /// Validates the config (throws core::ConfigError); throws core::ConfigError("range_max")
  /// unless range_max > 0 and finite.
  BeamModel(const BeamModelConfig& config, double range_max);

  /// The two sums of eq. (9) for one particle: the short part z_short p_short and the whole
  /// p_beam, both with normalised mixture weights (1/m).
  struct Terms {
    double short_part = 0.0;
    double total = 0.0;
  };
  /// Terms of a reading z (m) for an expected range z_star (m; kNoHit or anything >= range_max
  /// means range_max).
  Terms Evaluate(double z, double z_star) const;

  /// The per-reading factor exp(-λ z), shared by all particles (for EvaluateFast).
  double ShortDecay(double z) const;
  /// Evaluate with ShortDecay(z) precomputed; identical results.
  Terms EvaluateFast(double z, double short_decay, double z_star) const;

  /// Reused storage for SumTerms.
  struct Scratch {
    std::vector<double> zs, exponent, p_hit, p_short;
    std::vector<std::uint32_t> hit_side, short_side;
  };
  /// The two sums of eq. (9) for a reading z (m) over many expected ranges z_star (m):
  /// Σ_i w_i t_i.short_part and Σ_i w_i t_i.total with t_i = EvaluateFast(z, short_decay,
  /// z_star[i]), accumulated in the order i = 0, 1, ..., so bit for bit the sums of EvaluateFast's
  /// terms. weights: one per z_star, or empty for weights 1.
  Terms SumTerms(double z, double short_decay, std::span<const double> z_star,
                 std::span<const double> weights, Scratch* scratch) const;

  /// Bounds on one expected range's two parts of eq. (9) for a reading z (m) when all that is
  /// known of its z* is that it lies in (lo, range_max] (lo < 0: anywhere in [0, range_max];
  /// lo >= range_max: range_max, like a ray without a hit):
  /// the short part w_short p_short and the rest of p_beam (total − short part), each between
  /// its _lo and _hi (+inf where nothing bounds it). The dynamic-point test decides a beam from
  /// such bounds where they settle it (nav/dynamic_beam_test.hpp).
  struct TermBounds {
    double short_lo = 0.0, short_hi = 0.0, rest_lo = 0.0, rest_hi = 0.0;
  };
  TermBounds BoundsBeyond(double z, double short_decay, double lo) const;

  const BeamModelConfig& config() const { return config_; }
  double range_max() const { return range_max_; }

 private:
  double HitNormaliser(double z_star) const;  // Φ((range_max - z*)/σ) - Φ(-z*/σ)
  double ShortScale(double z_star) const;     // η λ = λ / (1 - exp(-λ z*)); 0 at z* = 0
  // SumTerms' passes. The first: per expected range, z* clamped to [0, range_max] and the
  // Gaussian's exponent, p_hit and p_short zeroed, and the lists of those on the hit side (an
  // exponential that does not underflow) and on the short side (z <= z*, z* > 0).
  void ListSides(double z, std::span<const double> z_star, Scratch* scratch, std::size_t* num_hit,
                 std::size_t* num_short) const;
  // p_hit (eq. 7) of the first num_hit ranges on the hit side list.
  void HitTerms(std::size_t num_hit, Scratch* scratch) const;
  // p_short (eq. 8) of the first num_short ranges on the short side list, and the weighted sum
  // of their short parts.
  double ShortTermsSum(std::size_t num_short, double short_decay, std::span<const double> weights,
                       Scratch* scratch) const;
  // The weighted sum of every range's p_beam.
  double TotalsSum(double z, std::span<const double> weights, const Scratch& s) const;
  BeamModelConfig config_;
  double range_max_;
  double w_hit_, w_short_, w_max_, w_rand_;  // mixture weights divided by their sum
  // The values of the z*-only factors at z* = range_max (no obstacle on the ray), computed once
  // by the same expressions as for any other z*.
  double hit_norm_at_max_ = 1.0;
  double short_scale_at_max_ = 0.0;
};

}  // namespace retrace::nav
