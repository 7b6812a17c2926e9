#include "nav/motion_model.hpp"

#include <cmath>

namespace retrace::nav {

void MotionModelConfig::Validate() const {
  core::RequireNonNegative("alpha1", alpha1);
  core::RequireNonNegative("alpha2", alpha2);
  core::RequireNonNegative("alpha3", alpha3);
  core::RequireNonNegative("alpha4", alpha4);
  core::RequireNonNegative("alpha_lateral", alpha_lateral);
}

MotionNoise MotionNoiseOf(const core::OdometryDelta& delta, const MotionModelConfig& config) {
  const double trans = std::abs(delta.distance);
  const double rot = std::abs(delta.dtheta);
  return {std::sqrt(config.alpha3 * trans + config.alpha4 * rot),
          std::sqrt(config.alpha1 * rot + config.alpha2 * trans),
          std::sqrt(config.alpha_lateral * trans)};
}

core::Pose2 SampleMotion(const core::Pose2& X_MR, const core::OdometryDelta& delta,
                         const MotionNoise& noise, core::Rng& rng) {
  if (delta.distance == 0.0 && delta.dtheta == 0.0) return X_MR;
  core::OdometryDelta noisy = delta;
  noisy.distance += noise.sigma_trans * rng.Normal();
  noisy.dtheta += noise.sigma_rot * rng.Normal();
  const core::Pose2 X = core::IntegrateOdometry(X_MR, noisy);  // eq. (2)
  if (noise.sigma_lateral == 0.0) return X;
  const double lateral = noise.sigma_lateral * rng.Normal();
  return {X.x - lateral * std::sin(X.theta), X.y + lateral * std::cos(X.theta), X.theta};
}

}  // namespace retrace::nav
