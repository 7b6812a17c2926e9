#pragma once
// The sample motion model of the localizer: paper eq. (2) with α-noise on one odometry
// increment, in the units of the simulated odometry's error model (sim/odometry.hpp).

#include "core/config.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "core/twist.hpp"

namespace retrace::nav {

/// Noise of the sample motion model. As in the odometry error model, the *variances* are
/// proportional to the motion, so the spread after a path does not depend on how finely it is
/// cut into increments (the original code used a variance formula as a standard deviation,
/// which shrank with the update rate):
///
///   σ²_rot   = alpha1 |δrot| + alpha2 |δtrans|     (rad²)
///   σ²_trans = alpha3 |δtrans| + alpha4 |δrot|     (m²)
///
///   σ²_lat   = alpha_lateral |δtrans|               (m², sideways, at the arc's end)
///
/// Units: alpha1 rad²/rad, alpha2 rad²/m, alpha3 m²/m, alpha4 m²/rad, alpha_lateral m²/m.
/// The lateral term is not in the odometry error model (wheels do not slip sideways in the
/// simulator): it lets the cloud explore sideways, where heading noise alone moves particles
/// only by δtrans·σ_rot per step, so that a lateral offset is corrected within a few updates
/// instead of a few hundred metres. Defaults are several times the simulated odometry's (2e-4,
/// 1e-5, 1e-3, 1e-4) so that the particles also cover its systematic errors the filter does not
/// model (1 % scale, 2.5e-4 wheel mismatch): per 0.2 m between updates, a distance std of
/// 2.4 cm (the scale error: 2 mm) and a heading std of 0.21° (the mismatch: 0.006°). They are
/// 0.7 times the earlier ones, from a sweep on real scans (docs/HISTORY.md, "Motion model
/// (eq. 2)"): a wider cloud drifts farther where most beams are rejected and locks onto the wrong
/// place after.
struct MotionModelConfig {
  double alpha1 = 1.4e-3;       ///< rad²/rad: heading noise from rotation
  double alpha2 = 7e-5;         ///< rad²/m: heading noise from translation
  double alpha3 = 2.8e-3;       ///< m²/m: distance noise from translation
  double alpha4 = 7e-4;         ///< m²/rad: distance noise from rotation
  double alpha_lateral = 7e-4;  ///< m²/m: sideways noise from translation

  template <class V>
  void Reflect(V& v) {
    v("alpha1", alpha1);
    v("alpha2", alpha2);
    v("alpha3", alpha3);
    v("alpha4", alpha4);
    v("alpha_lateral", alpha_lateral);
  }
  /// Throws core::ConfigError naming the key (e.g. "alpha3").
  void Validate() const;
};

/// Standard deviations (m, rad) of the distance, heading and sideways noise for one increment.
struct MotionNoise {
  double sigma_trans = 0.0;
  double sigma_rot = 0.0;
  double sigma_lateral = 0.0;
};
MotionNoise MotionNoiseOf(const core::OdometryDelta& delta, const MotionModelConfig& config);

/// Draws a successor of X_MR (M) for the odometry increment `delta` (robot frame): distance
/// and heading change perturbed by zero-mean Gaussians of MotionNoiseOf, integrated along the
/// arc exactly like the odometry (core::IntegrateOdometry), then shifted sideways (along the
/// final pose's y axis) by sigma_lateral N(0, 1). A zero increment returns X_MR unchanged and
/// draws nothing.
core::Pose2 SampleMotion(const core::Pose2& X_MR, const core::OdometryDelta& delta,
                         const MotionNoise& noise, core::Rng& rng);

}  // namespace retrace::nav
