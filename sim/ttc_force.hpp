#pragma once
// The anticipatory crowd model of Karamouzas, Skinner & Guy (2014, "Universal power law governing
// pedestrian interactions", Phys. Rev. Lett. 113, 238701) as pure functions, with a speed-headway
// rule for the desired speed. "Forces" are accelerations (m/s²); vectors are in the world frame W.
//
//   dv/dt = (v_pref - v) / xi                        driving term
//         + sum_b -grad_x E(tau_ab)                  other pedestrians (power law in the time to
//                                                    collision tau, E = k tau^-2 exp(-tau/tau0))
//         + robot and walls as in the social force   (social_force.hpp: their own, measured terms)
//
//   |v_pref| = min(v0, max(0, (s - l) / T))          speed-headway rule, and its direction the
//                                                    lane it picks (speed_headway.hpp)
//
// Someone walking the other way (headings more than 90° apart) is avoided sideways only: the
// force's part along the walking direction is dropped. Huber, Su, Krüger, Faschian, Glasauer &
// Hermsdörfer (2014, PLoS ONE 9, e89589) found walkers crossing another at obtuse angles adjust
// only their path, not their speed; kept, the braking part made counterflow stall (the power
// law's gradient for a nearly head-on course points mostly back along it).
//
// The power law alone brakes a person only for someone it is closing in on: in a stream where
// everyone walks alike, tau is infinite and nobody slows down however dense the crowd. The
// headway rule (Seyfried et al. 2005's linear speed-spacing relation, as in Tordeux, Chraibi &
// Seyfried's 2016 collision-free speed model) makes the desired speed depend on the space to the
// person ahead; docs/CROWD.md "Crowd check" says how its two parameters were fitted.

#include "core/config.hpp"
#include "core/pose2.hpp"
#include "sim/social_force.hpp"

namespace retrace::sim {

/// Parameters of the time-to-collision interaction and of its driving term. Defaults: the
/// values Karamouzas et al. fitted to their data (k = 1.5, tau0 = 3 s, xi = 0.54 s).
struct TtcForceConfig {
  double strength = 1.5;          ///< k (m²): the energy's scale, E = k tau^-2 exp(-tau/tau0)
  double time_horizon = 3.0;      ///< tau0 (s): interactions further ahead in time fade out
  double relaxation_time = 0.54;  ///< xi (s) of the driving term
  double range = 5.0;             ///< m: pedestrians farther than this (centres) are ignored
  /// Cap on the acceleration one neighbour can cause (m/s²): the gradient of tau grows without
  /// bound for a grazing course (the discriminant goes to 0).
  double max_pair_acceleration = 5.0;

  template <class V>
  void Reflect(V& v) {
    v("strength", strength);
    v("time_horizon", time_horizon);
    v("relaxation_time", relaxation_time);
    v("range", range);
    v("max_pair_acceleration", max_pair_acceleration);
  }
  /// Throws core::ConfigError naming the key: strength >= 0, the others > 0.
  void Validate() const;
};

/// Time (s) until two discs touch if both keep their velocities: x = x_a - x_b (m), v = v_a - v_b
/// (m/s), r = r_a + r_b (m). 0 if they already overlap, +inf if they are not on a collision
/// course.
double DiscTimeToCollision(const Vec2& x, const Vec2& v, double r);

/// The interaction energy E(tau) = k tau^-2 exp(-tau/tau0) (m²/s²); 0 for tau = +inf.
double TtcEnergy(double tau, const TtcForceConfig& config);

/// Force on `self` from `other`: -grad_x E(tau) with the analytic gradient of Karamouzas et al.
/// (eq. 2 of the paper), x = x_self - x_other, v = v_self - v_other. Zero when they are not on a
/// collision course or farther apart than config.range. Discs that already overlap by delta are
/// treated as discs of radius sum delta, so the force stays finite and the physics' contacts
/// separate them. Capped at config.max_pair_acceleration.
Vec2 TtcRepulsion(const SocialAgent& self, const SocialAgent& other, const TtcForceConfig& config);

/// Driving term (v_pref - v) / xi (m/s²) towards the preferred velocity `preferred` (W, m/s).
Vec2 TtcDrivingForce(const Vec2& velocity, const Vec2& preferred, const TtcForceConfig& config);

/// Total acceleration (m/s²) on a pedestrian: the driving term towards `preferred` (W, m/s: the
/// speed-headway rule's choice, not in.desired_speed along in.direction), the power law from
/// in.others (only its part square to in.direction from those whose heading is against
/// in.direction), and the robot and walls as SocialForce treats them (`social`: their strengths,
/// ranges, field of view and the walking-line rule for walls, all relative to in.direction).
/// Capped at social.max_acceleration.
Vec2 TtcForce(const SocialForceInputs& in, const Vec2& preferred, const TtcForceConfig& config,
              const SocialForceConfig& social);

}  // namespace retrace::sim
