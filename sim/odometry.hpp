#pragma once
// Simulated differential-drive wheel odometry: true wheel travel from ground truth, systematic
// wheel-radius errors, random noise of the odometry motion model, integrated into X_OR.

#include "core/config.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "core/twist.hpp"

namespace retrace::sim {

/// Wheel-odometry error model (docs/DESIGN.md §4).
///
/// One odometry step turns the true wheel travel d_L, d_R (m) into a measured increment:
///
///   systematic:  d_R' = (1 + scale_error) (1 + radius_mismatch / 2) d_R
///                d_L' = (1 + scale_error) (1 - radius_mismatch / 2) d_L
///                δtrans = (d_R' + d_L') / 2          (m, travelled arc length)
///                δrot   = (d_R' - d_L') / wheel_base (rad, heading change)
///
///   random (Probabilistic Robotics §5.4, odometry motion model; for a diff-drive step, an arc,
///   δrot1 = δrot2 = δrot / 2, so |δrot1| + |δrot2| = |δrot|). Unlike the book, whose standard
///   deviations are proportional to the motion, here the *variances* are, so the noise is a
///   random walk per metre and per radian and the accumulated drift does not depend on the
///   odometry rate (the original code's noise shrank as the rate grew):
///
///     σ²_rot   = alpha1 |δrot| + alpha2 |δtrans|     (rad²)
///     σ²_trans = alpha3 |δtrans| + alpha4 |δrot|     (m²)
///     distance = δtrans + σ_trans N(0, 1),  dtheta = δrot + σ_rot N(0, 1)
///
///   The noise goes on the total rotation and the translation only: an encoder increment has
///   two degrees of freedom, and the book's separate rot1/rot2 noise would only tilt the chord
///   within a step, an effect whose variance vanishes with the step length cubed.
///
///   Units: alpha1 rad²/rad (heading variance per radian turned), alpha2 rad²/m (heading
///   variance per metre travelled), alpha3 m²/m (distance variance per metre travelled),
///   alpha4 m²/rad (distance variance per radian turned).
///
/// Consequences on a straight run of length L (m): mean heading drift
/// (1 + scale_error) radius_mismatch L / wheel_base (rad, to the left when positive), heading
/// std sqrt(alpha2 L), along-track std sqrt(alpha3 L), lateral std from the heading random
/// walk sqrt(alpha2 L³ / 3), mean along-track error scale_error L.
///
/// Defaults: a 0.5 m wheel base robot with wheels calibrated to about 1 %. Per 100 m straight:
/// the radius mismatch of 2.5e-4 (the right wheel 0.025 % larger than the left, 0.04 mm on a
/// 15 cm wheel) turns the heading by 0.05 rad = 2.9° to the left, which bends the path sideways
/// by 2.5 m; the scale error adds 1 m along the track; the random walk adds a heading std of
/// sqrt(1e-5 · 100) = 0.032 rad = 1.8° (lateral std 1.8 m) and an along-track std of 0.32 m.
/// Measured over 200 seeds (tests/sim/odometry_test.cpp): RMS error after 100 m straight
/// 3.2 % of the distance and 3.2° of heading; after a 98 m square loop with rounded corners
/// 2.2 % and 6.9°, because the scale error also over-counts every turn by 1 % (3.6° per full
/// turn) and the rotation noise adds sqrt(2e-4 · 2π) = 0.035 rad = 2° per full turn.
struct OdometryConfig {
  double rate_hz = 50.0;            ///< odometry update rate (Hz); the episode schedules Update()
  double wheel_base = 0.5;          ///< distance between the wheels (m)
  double alpha1 = 2e-4;             ///< rad²/rad: heading noise from rotation
  double alpha2 = 1e-5;             ///< rad²/m: heading noise from translation
  double alpha3 = 1e-3;             ///< m²/m: distance noise from translation
  double alpha4 = 1e-4;             ///< m²/rad: distance noise from rotation
  double scale_error = 0.01;        ///< both radii as assumed / true - 1 (> 0: distances read long)
  double radius_mismatch = 2.5e-4;  ///< right minus left relative radius error (> 0: drifts left)

  template <class V>
  void Reflect(V& v) {
    v("rate_hz", rate_hz);
    v("wheel_base", wheel_base);
    v("alpha1", alpha1);
    v("alpha2", alpha2);
    v("alpha3", alpha3);
    v("alpha4", alpha4);
    v("scale_error", scale_error);
    v("radius_mismatch", radius_mismatch);
  }
  /// Throws core::ConfigError naming the offending key.
  void Validate() const;
};

/// Wheel odometry of one robot: integrates noisy encoder increments into the odometry pose X_OR,
/// which is the identity where the robot was when the odometry started (or was reset).
class Odometry {
 public:
  /// Throws core::ConfigError if the config is invalid.
  Odometry(const OdometryConfig& config, core::Rng rng);

  /// One odometry tick. From the ground-truth motion of the base between two ticks (poses X_WR
  /// in W), derives the true wheel travel (the motion projected on the heading: a diff-drive
  /// cannot slip sideways, so lateral slip, e.g. from collisions, is not measured), applies the
  /// systematic errors and the noise, integrates the result into X_OR (exactly, as a circular
  /// arc: see core::IntegrateOdometry) and returns the measured increment (m, rad).
  core::OdometryDelta Update(const core::Pose2& X_WR_prev, const core::Pose2& X_WR_now);

  /// The odometry pose X_OR (m, rad).
  const core::Pose2& pose() const { return X_OR_; }
  /// Restarts integration from X_OR (identity by default).
  void Reset(const core::Pose2& X_OR = {});

  const OdometryConfig& config() const { return config_; }

 private:
  OdometryConfig config_;
  core::Rng rng_;
  core::Pose2 X_OR_;
};

}  // namespace retrace::sim
