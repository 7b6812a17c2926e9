#include "nav/beam_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/check.hpp"
#include "core/config.hpp"
#include "core/errors.hpp"

namespace retrace::nav {
namespace {

// Standard normal cumulative distribution.
double Phi(double u) { return 0.5 * std::erfc(-u * std::numbers::sqrt2 / 2.0); }

// Beyond this many σ from both ends of [0, range_max] the Gaussian's mass outside the interval
// (below 1.2e-19 per side) vanishes in double precision: the normaliser is exactly 1.
constexpr double kNormaliserFreeSigmas = 9.0;

}  // namespace

void BeamModelConfig::Validate() const {
  core::RequireNonNegative("z_hit", z_hit);
  core::RequireNonNegative("z_short", z_short);
  core::RequireNonNegative("z_max", z_max);
  core::RequireNonNegative("z_rand", z_rand);
  if (!(z_hit + z_short + z_max + z_rand > 0.0)) {
    throw core::ConfigError("z_hit",
                            "the mixture weights z_hit, z_short, z_max, z_rand must not all be 0");
  }
  core::RequirePositive("sigma_hit", sigma_hit);
  core::RequirePositive("lambda_short", lambda_short);
}

BeamModel::BeamModel(const BeamModelConfig& config, double range_max)
    : config_(config), range_max_(range_max) {
  config_.Validate();
  if (!(range_max > 0.0) || !std::isfinite(range_max)) {
    throw core::ConfigError("range_max", "must be > 0, got " + core::FormatNumber(range_max));
  }
  const double sum = config_.z_hit + config_.z_short + config_.z_max + config_.z_rand;
  w_hit_ = config_.z_hit / sum;
  w_short_ = config_.z_short / sum;
  w_max_ = config_.z_max / sum;
  w_rand_ = config_.z_rand / sum;
  hit_norm_at_max_ = HitNormaliser(range_max_);
  short_scale_at_max_ = ShortScale(range_max_);
}

double BeamModel::HitNormaliser(double zs) const {
  const double sigma = config_.sigma_hit;
  const bool interior =
      zs >= kNormaliserFreeSigmas * sigma && range_max_ - zs >= kNormaliserFreeSigmas * sigma;
  return interior ? 1.0 : Phi((range_max_ - zs) / sigma) - Phi(-zs / sigma);
}

double BeamModel::ShortScale(double zs) const {
  const double lambda = config_.lambda_short;
  return zs > 0.0 ? lambda / (1.0 - std::exp(-lambda * zs)) : 0.0;
}

double BeamModel::ShortDecay(double z) const { return std::exp(-config_.lambda_short * z); }

BeamModel::Terms BeamModel::Evaluate(double z, double z_star) const {
  return EvaluateFast(z, ShortDecay(z), z_star);
}

BeamModel::TermBounds BeamModel::BoundsBeyond(double z, double short_decay, double lo) const {
  TermBounds b;
  if (z < 0.0) return b;  // no term (EvaluateFast's early return)
  const double p_max = z >= range_max_ ? 1.0 : 0.0;
  const double p_rand = z < range_max_ ? 1.0 / range_max_ : 0.0;
  const double floor = w_max_ * p_max + w_rand_ * p_rand;  // the part that ignores z*
  const double zs_lo = std::clamp(lo, 0.0, range_max_);    // z* in (zs_lo, range_max]
  // eq. (8): p_short is on for z <= z* (z* > 0) and falls as z* grows (ShortScale decreases), so
  // it is least at range_max when every z* there is on the short side, and greatest at the
  // smallest z* on the short side.
  if (z <= zs_lo && z <= range_max_) b.short_lo = w_short_ * short_scale_at_max_ * short_decay;
  const double first_short = std::max(zs_lo, z);
  if (first_short <= range_max_) {
    b.short_hi = first_short > 0.0 ? w_short_ * ShortScale(first_short) * short_decay
                                   : std::numeric_limits<double>::infinity();
  }
  // eq. (7): the Gaussian is greatest at the z* nearest to z, and its normaliser (the mass of
  // N(z*, σ²) inside [0, range_max]) is least at an end of the interval, as it rises towards
  // range_max / 2 and falls beyond.
  b.rest_lo = floor;
  b.rest_hi = floor;
  if (z <= range_max_) {
    const double sigma = config_.sigma_hit;
    const double a = std::max(zs_lo - z, 0.0) / sigma;
    const double g = std::exp(-0.5 * a * a) / (std::sqrt(2.0 * std::numbers::pi) * sigma);
    const double norm = std::min(HitNormaliser(zs_lo), hit_norm_at_max_);
    b.rest_hi += norm > 0.0 ? w_hit_ * g / norm : std::numeric_limits<double>::infinity();
  }
  return b;
}

BeamModel::Terms BeamModel::EvaluateFast(double z, double short_decay, double z_star) const {
  // No obstacle on the ray (kNoHit) or beyond the sensor: the map expects a max-range reading.
  const double zs = z_star >= range_max_ ? range_max_ : std::max(z_star, 0.0);
  const double sigma = config_.sigma_hit;
  Terms terms;
  if (z < 0.0) return terms;
  const bool at_max = zs == range_max_;
  // eq. (7): p_hit, a Gaussian around z* normalised over [0, range_max].
  double p_hit = 0.0;
  if (z <= range_max_) {
    const double a = (z - zs) / sigma;
    // Beyond 38.6 σ the exponential underflows to exactly 0: skipping it changes nothing.
    if (a * a < 1490.0) {
      const double g = std::exp(-0.5 * a * a) / (std::sqrt(2.0 * std::numbers::pi) * sigma);
      const double norm = at_max ? hit_norm_at_max_ : HitNormaliser(zs);
      p_hit = norm > 0.0 ? g / norm : 0.0;
    }
  }
  // eq. (8): p_short, a truncated exponential on [0, z*].
  double p_short = 0.0;
  if (zs > 0.0 && z <= zs) p_short = (at_max ? short_scale_at_max_ : ShortScale(zs)) * short_decay;
  const double p_max = z >= range_max_ ? 1.0 : 0.0;
  const double p_rand = z < range_max_ ? 1.0 / range_max_ : 0.0;
  terms.short_part = w_short_ * p_short;
  terms.total = w_hit_ * p_hit + terms.short_part + w_max_ * p_max + w_rand_ * p_rand;
  return terms;
}

inline void BeamModel::ListSides(double z, std::span<const double> z_star, Scratch* scratch,
                                 std::size_t* num_hit, std::size_t* num_short) const {
  Scratch& s = *scratch;
  const std::size_t n = z_star.size();
  const double sigma = config_.sigma_hit;
  const bool in_range = z <= range_max_;
  std::size_t hits = 0, shorts = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double zs = z_star[i] >= range_max_ ? range_max_ : std::max(z_star[i], 0.0);
    s.zs[i] = zs;
    // eq. (7): p_hit where the Gaussian does not underflow to exactly 0 (within 38.6 σ).
    const double a = (z - zs) / sigma;
    s.exponent[i] = -0.5 * a * a;
    s.p_hit[i] = 0.0;
    s.hit_side[hits] = static_cast<std::uint32_t>(i);
    hits += (in_range & (a * a < 1490.0)) ? 1 : 0;
    // eq. (8): p_short on the short side, z <= z* (and z* > 0).
    s.p_short[i] = 0.0;
    s.short_side[shorts] = static_cast<std::uint32_t>(i);
    shorts += ((zs > 0.0) & (z <= zs)) ? 1 : 0;
  }
  *num_hit = hits;
  *num_short = shorts;
}

inline void BeamModel::HitTerms(std::size_t num_hit, Scratch* scratch) const {
  Scratch& s = *scratch;
  const double sigma = config_.sigma_hit;
  const double gauss_scale = std::sqrt(2.0 * std::numbers::pi) * sigma;
  for (std::size_t k = 0; k < num_hit; ++k) {
    const std::size_t i = s.hit_side[k];
    const double g = std::exp(s.exponent[i]) / gauss_scale;
    const double zs = s.zs[i];
    // HitNormaliser is exactly 1 in the interior, and g / 1 is g.
    const bool interior =
        zs >= kNormaliserFreeSigmas * sigma && range_max_ - zs >= kNormaliserFreeSigmas * sigma;
    if (interior) {
      s.p_hit[i] = g;
    } else {
      const double norm = zs == range_max_ ? hit_norm_at_max_ : HitNormaliser(zs);
      s.p_hit[i] = norm > 0.0 ? g / norm : 0.0;
    }
  }
}

inline double BeamModel::ShortTermsSum(std::size_t num_short, double short_decay,
                                       std::span<const double> weights, Scratch* scratch) const {
  Scratch& s = *scratch;
  double sum_short = 0.0;
  for (std::size_t k = 0; k < num_short; ++k) {
    const std::size_t i = s.short_side[k];
    const double zs = s.zs[i];
    s.p_short[i] = (zs == range_max_ ? short_scale_at_max_ : ShortScale(zs)) * short_decay;
    sum_short += (weights.empty() ? 1.0 : weights[i]) * (w_short_ * s.p_short[i]);
  }
  return sum_short;
}

inline double BeamModel::TotalsSum(double z, std::span<const double> weights,
                                   const Scratch& s) const {
  const std::size_t n = s.zs.size();
  const double p_max = z >= range_max_ ? 1.0 : 0.0;
  const double p_rand = z < range_max_ ? 1.0 / range_max_ : 0.0;
  const double max_part = w_max_ * p_max, rand_part = w_rand_ * p_rand;
  double sum_total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    const double total = w_hit_ * s.p_hit[i] + w_short_ * s.p_short[i] + max_part + rand_part;
    sum_total += w * total;
  }
  return sum_total;
}

BeamModel::Terms BeamModel::SumTerms(double z, double short_decay, std::span<const double> z_star,
                                     std::span<const double> weights, Scratch* scratch) const {
  // EvaluateFast's values by the same operations, in passes over the expected ranges: first
  // everything before the exponentials, listing the ranges that need one; then the terms that
  // need an exponential, each kind in a loop of its own with little else to keep in registers
  // across the calls; then the sums, in the order in which EvaluateFast's terms would be summed.
  // The lists also replace the test z <= z*, a coin toss for the branch predictor when the
  // reading agrees with the map.
  const std::size_t n = z_star.size();
  RETRACE_CHECK(weights.empty() || weights.size() == n);
  Terms sums;
  if (z < 0.0 || n == 0) return sums;  // no term (EvaluateFast's early return)
  Scratch& s = *scratch;
  s.zs.resize(n);
  s.exponent.resize(n);
  s.p_hit.resize(n);
  s.p_short.resize(n);
  s.hit_side.resize(n);
  s.short_side.resize(n);
  std::size_t num_hit = 0, num_short = 0;
  ListSides(z, z_star, &s, &num_hit, &num_short);
  HitTerms(num_hit, &s);
  // The short part's term in its sum is w * (z_short * 0) = +0 off the short side, which leaves
  // the sum unchanged: that sum runs over the short side only. (Two sums in two loops: GCC pairs
  // two accumulators of one loop in a vector that it keeps in memory, a store-to-load round trip
  // in every addition.)
  sums.short_part = ShortTermsSum(num_short, short_decay, weights, &s);
  sums.total = TotalsSum(z, weights, s);
  return sums;
}

}  // namespace retrace::nav
