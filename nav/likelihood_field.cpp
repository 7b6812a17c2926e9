#include "nav/likelihood_field.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/check.hpp"
#include "core/config.hpp"
#include "core/errors.hpp"

namespace retrace::nav {
namespace {

// A squared distance larger than any real one (cells²) that keeps the parabola arithmetic
// finite (no inf - inf).
constexpr double kFar = 1e20;

// One-dimensional squared-distance transform of a sampled function f (Felzenszwalb and
// Huttenlocher 2012): d[q] = min_p (q - p)² + f[p]. v, z are scratch of sizes n and n + 1.
void DistanceTransform1d(const double* f, int n, double* d, int* v, double* z) {
  const auto intersect = [f](int q, int p) {
    return ((f[q] + static_cast<double>(q) * q) - (f[p] + static_cast<double>(p) * p)) /
           (2.0 * (q - p));
  };
  int k = 0;
  v[0] = 0;
  z[0] = -std::numeric_limits<double>::infinity();
  z[1] = std::numeric_limits<double>::infinity();
  for (int q = 1; q < n; ++q) {
    double s = intersect(q, v[k]);
    while (s <= z[k]) {  // terminates at k = 0 because z[0] = -inf
      --k;
      s = intersect(q, v[k]);
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = std::numeric_limits<double>::infinity();
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    const double dq = q - v[k];
    d[q] = dq * dq + f[v[k]];
  }
}

}  // namespace

void LikelihoodFieldConfig::Validate() const {
  core::RequireInRange("occupied_threshold", occupied_threshold, 0.5, 1.0);
  if (!(occupied_threshold > 0.5)) {
    throw core::ConfigError("occupied_threshold", "must be > 0.5 (unknown cells are 0.5)");
  }
  core::RequirePositive("max_distance", max_distance);
  core::RequirePositive("sigma_hit", sigma_hit);
  core::RequireNonNegative("z_hit", z_hit);
  core::RequirePositive("z_rand", z_rand);
}

std::vector<float> DistanceTransformCells(const std::vector<std::uint8_t>& occupied, int width,
                                          int height) {
  RETRACE_CHECK(width >= 0 && height >= 0);
  const std::size_t w = static_cast<std::size_t>(width);
  const std::size_t h = static_cast<std::size_t>(height);
  RETRACE_CHECK(occupied.size() == w * h);
  std::vector<float> out(w * h, std::numeric_limits<float>::infinity());
  if (w == 0 || h == 0) return out;
  const std::size_t n_max = std::max(w, h);
  std::vector<double> f(n_max), d(n_max), z(n_max + 1);
  std::vector<int> v(n_max);
  std::vector<double> columns(w * h);  // squared distances after the column pass
  // Pass 1: along each column (y).
  for (std::size_t x = 0; x < w; ++x) {
    for (std::size_t y = 0; y < h; ++y) f[y] = occupied[y * w + x] != 0 ? 0.0 : kFar;
    DistanceTransform1d(f.data(), height, d.data(), v.data(), z.data());
    for (std::size_t y = 0; y < h; ++y) columns[y * w + x] = d[y];
  }
  // Pass 2: along each row (x).
  for (std::size_t y = 0; y < h; ++y) {
    DistanceTransform1d(columns.data() + y * w, width, d.data(), v.data(), z.data());
    for (std::size_t x = 0; x < w; ++x) {
      out[y * w + x] = d[x] >= 0.5 * kFar ? std::numeric_limits<float>::infinity()
                                          : static_cast<float>(std::sqrt(d[x]));
    }
  }
  return out;
}

LikelihoodField::LikelihoodField(const core::OccupancyGrid& map,
                                 const LikelihoodFieldConfig& config, double range_max)
    : config_(config), range_max_(range_max) {
  config_.Validate();
  if (!(range_max > 0.0) || !std::isfinite(range_max)) {
    throw core::ConfigError("range_max", "must be > 0, got " + core::FormatNumber(range_max));
  }
  width_ = map.width();
  height_ = map.height();
  width_d_ = width_;
  height_d_ = height_;
  resolution_ = map.resolution();
  inv_resolution_ = 1.0 / resolution_;
  origin_ = map.origin();
  outside_log_likelihood_ = static_cast<float>(std::log(config_.z_rand / range_max_));

  const std::size_t n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  // Probability >= threshold, evaluated as log-odds >= logit(threshold) (same order).
  const double occupied_log_odds = core::Logit(config_.occupied_threshold);
  occupied_.resize(n);
  const std::vector<float>& l = map.log_odds();
  for (std::size_t i = 0; i < n; ++i) occupied_[i] = static_cast<double>(l[i]) >= occupied_log_odds;
  const double known_log_odds = core::Logit(kKnownProbability);
  known_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    known_[i] = std::abs(static_cast<double>(l[i])) >= known_log_odds;
  }

  distance_ = DistanceTransformCells(occupied_, width_, height_);
  log_likelihood_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    distance_[i] = static_cast<float>(static_cast<double>(distance_[i]) * resolution_);
    // A surface lies somewhere inside its occupied cell, on average half a cell from the face
    // the beams meet: a free cell's centre is d - res/2 from it. Without the correction the
    // field prefers end points inside the wall cells and biases poses by about half a cell.
    const double d = std::max(0.0, static_cast<double>(distance_[i]) - 0.5 * resolution_);
    log_likelihood_[i] = static_cast<float>(LogLikelihoodOfDistance(d));
  }
}

double LikelihoodField::LogLikelihoodOfDistance(double d) const {
  const double dt = std::min(d, config_.max_distance);
  const double sigma = config_.sigma_hit;
  const double p_hit =
      std::exp(-dt * dt / (2.0 * sigma * sigma)) / (std::sqrt(2.0 * std::numbers::pi) * sigma);
  return std::log(config_.z_hit * p_hit + config_.z_rand / range_max_);  // eq. (5-6)
}

template <class Term>
double LikelihoodField::SumOverEndPoints(const core::Pose2& X_ML, const double* xs_L,
                                         const double* ys_L, std::size_t n, Term term) const {
  const double c = std::cos(X_ML.theta);
  const double s = std::sin(X_ML.theta);
  const double ox = origin_.x();
  const double oy = origin_.y();
  const float* table = log_likelihood_.data();
  const float outside = outside_log_likelihood_;
  const std::size_t w = static_cast<std::size_t>(width_);
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    // Same arithmetic as LogLikelihood(X_ML * p_L), so both give the same cell.
    const double gx = (X_ML.x + c * xs_L[i] - s * ys_L[i] - ox) * inv_resolution_;
    const double gy = (X_ML.y + s * xs_L[i] + c * ys_L[i] - oy) * inv_resolution_;
    const bool inside = gx >= 0.0 && gy >= 0.0 && gx < width_d_ && gy < height_d_;
    const std::size_t idx =
        inside ? static_cast<std::size_t>(static_cast<int>(gy)) * w +
                     static_cast<std::size_t>(static_cast<int>(gx))
               : 0;
    sum += term(i, inside ? table[idx] : outside);
  }
  return sum;
}

double LikelihoodField::SumLogLikelihood(const core::Pose2& X_ML, const double* xs_L,
                                         const double* ys_L, std::size_t n) const {
  if (log_likelihood_.empty()) return static_cast<double>(n) * outside_log_likelihood_;
  return SumOverEndPoints(X_ML, xs_L, ys_L, n,
                          [](std::size_t, float ll) { return static_cast<double>(ll); });
}

double LikelihoodField::SumLogMixture(const core::Pose2& X_ML, const double* xs_L,
                                      const double* ys_L, const double* floor, double scale,
                                      std::size_t n) const {
  const auto mixture = [&](std::size_t i, float ll) {
    return std::log(scale * static_cast<double>(std::exp(ll)) + floor[i]);
  };
  if (log_likelihood_.empty()) {
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) sum += mixture(i, outside_log_likelihood_);
    return sum;
  }
  return SumOverEndPoints(X_ML, xs_L, ys_L, n, mixture);
}

}  // namespace retrace::nav
