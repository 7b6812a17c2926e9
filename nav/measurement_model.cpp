#include "nav/measurement_model.hpp"

#include <cmath>

#include "core/check.hpp"

namespace retrace::nav {

void ClassConditionalConfig::Validate() const {
  core::RequireInRange("mapped_prior", mapped_prior, 0.0, 1.0);
  if (!(mapped_prior > 0.0)) throw core::ConfigError("mapped_prior", "must be > 0");
  core::RequirePositive("lambda_unknown", lambda_unknown);
  core::RequireInRange("unknown_threshold", unknown_threshold, 0.0, 1.0);
}

double ClassConditionalConfig::UnknownDensity(double z, double range_max) const {
  const double lambda = lambda_unknown;
  return (1.0 - mapped_prior) * lambda * std::exp(-lambda * z) /
         (1.0 - std::exp(-lambda * range_max));
}

double ScanLogLikelihood(const LikelihoodField& field, const core::Pose2& X_ML,
                         const WeighedPoints& points) {
  RETRACE_CHECK(points.xs.size() == points.ys.size());
  if (points.unknown.empty()) {
    return field.SumLogLikelihood(X_ML, points.xs.data(), points.ys.data(), points.size());
  }
  RETRACE_CHECK(points.unknown.size() == points.size());
  return field.SumLogMixture(X_ML, points.xs.data(), points.ys.data(), points.unknown.data(),
                             points.mapped_prior, points.size());
}

std::vector<double> UnknownPosterior(const LikelihoodField& field, const core::Pose2& X_ML,
                                     const WeighedPoints& points) {
  RETRACE_CHECK(points.unknown.size() == points.size());
  std::vector<double> posterior(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const core::Vec2 end = (X_ML * core::Pose2(points.xs[i], points.ys[i], 0.0)).translation();
    const double mapped =
        points.mapped_prior * std::exp(static_cast<double>(field.LogLikelihood(end)));
    posterior[i] = points.unknown[i] / (mapped + points.unknown[i]);
  }
  return posterior;
}

}  // namespace retrace::nav
