#include "nav/beam_model.hpp"

#include <cmath>
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
    throw core::ConfigError("z_hit", "the mixture weights z_hit, z_short, z_max, z_rand must not all be 0");
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
  const bool interior = zs >= kNormaliserFreeSigmas * sigma &&
                        range_max_ - zs >= kNormaliserFreeSigmas * sigma;
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
  std::vector<double> z(nb), decay(nb), ux(nb), uy(nb), num(nb, 0.0), den(nb, 0.0);
  const std::size_t np = X_ML.size();
  std::vector<double> pc(np), ps(np), pw(np);
  for (std::size_t b = 0; b < nb; ++b) {
    const int i = beams[b];
    RETRACE_CHECK(i >= 0 && static_cast<std::size_t>(i) < scan.size() &&
                  scan.Valid(static_cast<std::size_t>(i)));
    z[b] = scan.ranges[static_cast<std::size_t>(i)];
    decay[b] = model.ShortDecay(z[b]);
    const double a = scan.Angle(static_cast<std::size_t>(i));
    ux[b] = std::cos(a);
    uy[b] = std::sin(a);
  }
  const double range_max = model.range_max();
  // The particles that take part (zero weights add nothing to either sum), in order.
  std::vector<std::size_t> used;
  used.reserve(np);
  for (std::size_t j = 0; j < np; ++j) {
    pc[j] = std::cos(X_ML[j].theta);  // one rotation per particle
    ps[j] = std::sin(X_ML[j].theta);
    pw[j] = weights.empty() ? 1.0 : weights[j];
    if (pw[j] > 0.0) used.push_back(j);
  }
  const std::size_t nu = used.size();
  std::vector<double> px(nu), py(nu), rx(nu), ry(nu), z_star(nu);
  for (std::size_t u = 0; u < nu; ++u) {
    px[u] = X_ML[used[u]].x;
    py[u] = X_ML[used[u]].y;
  }
  // Beam-major order: the particles' rays of one beam run side by side over the same cells,
  // so consecutive casts hit the cache.
  for (std::size_t b = 0; b < nb; ++b) {
    for (std::size_t u = 0; u < nu; ++u) {
      const std::size_t j = used[u];
      rx[u] = pc[j] * ux[b] - ps[j] * uy[b];
      ry[u] = ps[j] * ux[b] + pc[j] * uy[b];
    }
    if (method == RayCastMethod::kSphereTracing) {
      caster.CastMany(px, py, rx, ry, range_max, z_star);
    } else {
      for (std::size_t u = 0; u < nu; ++u) z_star[u] = caster.CastDda(px[u], py[u], rx[u], ry[u], range_max);
    }
    double sum_short = 0.0, sum_total = 0.0;
    for (std::size_t u = 0; u < nu; ++u) {
      const double w = pw[used[u]];
      const BeamModel::Terms t = model.EvaluateFast(z[b], decay[b], z_star[u]);
      sum_short += w * t.short_part;
      sum_total += w * t.total;
    }
    num[b] = sum_short;
    den[b] = sum_total;
  }
  for (std::size_t b = 0; b < nb; ++b) {
    const double r = den[b] > 0.0 ? num[b] / den[b] : 0.0;  // eq. (9)
    result->ratio[b] = r;
    result->dynamic[b] = r > chi ? 1 : 0;
  }
}

}  // namespace retrace::nav
