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

namespace {

// For each tested beam b (index beams[b] into the scan, checked valid): its reading z[b] (m),
// the short decay of that reading, and its unit direction (ux[b], uy[b]) in L.
void ReadTestedBeams(const BeamModel& model, const core::LaserScan& scan,
                     std::span<const int> beams, std::span<double> z, std::span<double> decay,
                     std::span<double> ux, std::span<double> uy) {
  for (std::size_t b = 0; b < beams.size(); ++b) {
    const int i = beams[b];
    RETRACE_CHECK(i >= 0 && static_cast<std::size_t>(i) < scan.size() &&
                  scan.Valid(static_cast<std::size_t>(i)));
    z[b] = scan.ranges[static_cast<std::size_t>(i)];
    decay[b] = model.ShortDecay(z[b]);
    const double a = scan.Angle(static_cast<std::size_t>(i));
    ux[b] = std::cos(a);
    uy[b] = std::sin(a);
  }
}

// The particles that take part in the dynamic-point test (zero weights add nothing to either
// sum), in the order of their headings: consecutive rays of a beam then point in nearly the same
// direction, and CastMany clears their common start once per bundle. The sums stay in particle
// order: order[k] is the place in it of the k-th particle by heading.
struct DynamicTestParticles {
  std::vector<std::size_t> order;
  std::vector<double> px, py, c, s;  // position (M) and rotation (cos, sin of the heading)
  std::vector<double> w_used;        // the weights in particle order; empty for equal weights
};

DynamicTestParticles SortedTestParticles(std::span<const core::Pose2> X_ML,
                                         std::span<const double> weights) {
  const std::size_t np = X_ML.size();
  std::vector<double> pc(np), ps(np), pw(np);
  std::vector<std::size_t> used;
  used.reserve(np);
  for (std::size_t j = 0; j < np; ++j) {
    pc[j] = std::cos(X_ML[j].theta);  // one rotation per particle
    ps[j] = std::sin(X_ML[j].theta);
    pw[j] = weights.empty() ? 1.0 : weights[j];
    if (pw[j] > 0.0) used.push_back(j);
  }
  const std::size_t nu = used.size();
  DynamicTestParticles p;
  if (!weights.empty()) {
    for (const std::size_t j : used) p.w_used.push_back(pw[j]);
  }
  // (A NaN heading sorts last: it must not break the ordering std::sort relies on.)
  p.order.resize(nu);
  std::vector<double> heading(nu);
  for (std::size_t u = 0; u < nu; ++u) {
    p.order[u] = u;
    const double theta = X_ML[used[u]].theta;
    heading[u] = std::isnan(theta) ? std::numeric_limits<double>::infinity() : theta;
  }
  std::sort(p.order.begin(), p.order.end(), [&](std::size_t a, std::size_t b) {
    return heading[a] < heading[b] || (heading[a] == heading[b] && a < b);
  });
  p.px.resize(nu);
  p.py.resize(nu);
  p.c.resize(nu);
  p.s.resize(nu);
  for (std::size_t k = 0; k < nu; ++k) {
    const std::size_t j = used[p.order[k]];
    p.px[k] = X_ML[j].x;
    p.py[k] = X_ML[j].y;
    p.c[k] = pc[j];
    p.s[k] = ps[j];
  }
  return p;
}

}  // namespace

void TestDynamicBeams(const BeamModel& model, const GridRayCaster& caster,
                      std::span<const core::Pose2> X_ML, std::span<const double> weights,
                      const core::LaserScan& scan, std::span<const int> beams, double chi,
                      RayCastMethod method, DynamicBeamResult* result) {
  RETRACE_CHECK(result != nullptr);
  RETRACE_CHECK(weights.empty() || weights.size() == X_ML.size());
  const std::size_t nb = beams.size();
  result->dynamic.assign(nb, 0);
  result->ratio.assign(nb, 0.0);
  if (nb == 0 || X_ML.empty()) return;
  std::vector<double> z(nb), decay(nb), ux(nb), uy(nb);
  ReadTestedBeams(model, scan, beams, z, decay, ux, uy);
  const DynamicTestParticles p = SortedTestParticles(X_ML, weights);
  const std::size_t nu = p.order.size();
  const double range_max = model.range_max();
  BeamModel::Scratch scratch;
  std::vector<double> rx(nu), ry(nu), z_cast(nu), z_star(nu);
  // Beam-major order: the particles' rays of one beam run side by side over the same cells,
  // so consecutive casts hit the cache.
  for (std::size_t b = 0; b < nb; ++b) {
    for (std::size_t k = 0; k < nu; ++k) {
      rx[k] = p.c[k] * ux[b] - p.s[k] * uy[b];
      ry[k] = p.s[k] * ux[b] + p.c[k] * uy[b];
    }
    if (method == RayCastMethod::kSphereTracing) {
      caster.CastMany(p.px, p.py, rx, ry, range_max, z_cast);
      for (std::size_t k = 0; k < nu; ++k) z_star[p.order[k]] = z_cast[k];
    } else {
      for (std::size_t k = 0; k < nu; ++k) {
        z_star[p.order[k]] = caster.CastDda(p.px[k], p.py[k], rx[k], ry[k], range_max);
      }
    }
    const BeamModel::Terms sums = model.SumTerms(z[b], decay[b], z_star, p.w_used, &scratch);
    const double r = sums.total > 0.0 ? sums.short_part / sums.total : 0.0;  // eq. (9)
    result->ratio[b] = r;
    result->dynamic[b] = r > chi ? 1 : 0;
  }
}

}  // namespace retrace::nav
