#include "sim/odometry.hpp"

#include <cmath>

#include "core/angle.hpp"
#include "core/check.hpp"

namespace retrace::sim {

void OdometryConfig::Validate() const {
  core::RequireInRange("rate_hz", rate_hz, 1e-3, 1000.0);
  core::RequirePositive("wheel_base", wheel_base);
  core::RequireNonNegative("alpha1", alpha1);
  core::RequireNonNegative("alpha2", alpha2);
  core::RequireNonNegative("alpha3", alpha3);
  core::RequireNonNegative("alpha4", alpha4);
  core::RequireInRange("scale_error", scale_error, -0.5, 0.5);
  core::RequireInRange("radius_mismatch", radius_mismatch, -0.1, 0.1);
}

Odometry::Odometry(const OdometryConfig& config, core::Rng rng) : config_(config), rng_(rng) {
  config_.Validate();
}

void Odometry::Reset(const core::Pose2& X_OR) { X_OR_ = X_OR; }

core::OdometryDelta Odometry::Update(const core::Pose2& X_WR_prev, const core::Pose2& X_WR_now) {
  // True motion in the previous robot frame. A diff-drive moves on an arc: its chord points
  // along the midpoint heading dθ/2; the component across it is slip the wheels do not see.
  const core::Pose2 X_RprevRnow = core::Between(X_WR_prev, X_WR_now);
  const double dtheta = X_RprevRnow.theta;  // in [-pi, pi): steps are short
  const double half = 0.5 * dtheta;
  const double chord = X_RprevRnow.x * std::cos(half) + X_RprevRnow.y * std::sin(half);
  const double arc = chord / core::Sinc(half);  // core::Sinc(half) >= 2/pi for |half| <= pi/2

  // True wheel travel, then the encoders' view of it through the miscalibrated radii.
  const double b = config_.wheel_base;
  const double d_right = arc + 0.5 * b * dtheta;
  const double d_left = arc - 0.5 * b * dtheta;
  const double scale = 1.0 + config_.scale_error;
  const double d_right_meas = scale * (1.0 + 0.5 * config_.radius_mismatch) * d_right;
  const double d_left_meas = scale * (1.0 - 0.5 * config_.radius_mismatch) * d_left;
  const double trans = 0.5 * (d_right_meas + d_left_meas);
  const double rot = (d_right_meas - d_left_meas) / b;

  // Random walk per metre and per radian: variances proportional to the step's motion, so the
  // accumulated variance does not depend on how finely the motion is cut into steps.
  const double var_rot = config_.alpha1 * std::abs(rot) + config_.alpha2 * std::abs(trans);
  const double var_trans = config_.alpha3 * std::abs(trans) + config_.alpha4 * std::abs(rot);
  // Always draw both numbers so that the stream does not depend on whether the robot moved.
  const double n_rot = rng_.Normal();
  const double n_trans = rng_.Normal();

  core::OdometryDelta delta;
  delta.distance = trans + std::sqrt(var_trans) * n_trans;
  delta.dtheta = rot + std::sqrt(var_rot) * n_rot;
  RETRACE_CHECK(std::isfinite(delta.distance) && std::isfinite(delta.dtheta));
  X_OR_ = core::IntegrateOdometry(X_OR_, delta);
  return delta;
}


}  // namespace retrace::sim
