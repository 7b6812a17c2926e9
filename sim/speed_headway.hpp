#pragma once
// The speed-headway rule: a pedestrian walks no faster than the space to the person ahead allows,
// v = min(v0, max(0, (s - l) / T)) for a headway s (m) between the centres, a length l (m) and a
// time gap T (s). Seyfried, Steffen, Klingsch & Boltes (2005, J. Stat. Mech. P10002) measured
// this linear speed-spacing relation in single file; Tordeux, Chraibi & Seyfried (2016,
// "Collision-free speed model for pedestrian dynamics") use it in two dimensions, with the
// headway to the nearest person whose body lies in the walker's path. Pure functions; vectors in
// the world frame W.

#include <span>

#include "core/config.hpp"
#include "core/pose2.hpp"
#include "sim/social_force.hpp"

namespace retrace::sim {

/// The rule's parameters (docs/CROWD.md "Crowd check": l and T fitted to Weidmann's curve).
struct SpeedHeadwayConfig {
  double length = 0.2;     ///< l (m): the headway at which a walker stops
  double time_gap = 0.95;  ///< T (s): how much each second of walking needs of headway
  bool enabled = true;     ///< false: the headway never reduces the speed

  template <class V>
  void Reflect(V& v) {
    v("length", length);
    v("time_gap", time_gap);
    v("enabled", enabled);
  }
  /// Throws core::ConfigError naming the key: length >= 0, time_gap > 0.
  void Validate() const;
};

/// Headway (m) of `self` walking along the unit vector `direction`: the centre distance to the
/// nearest of `others` that lies ahead (positive along `direction`) and whose body overlaps the
/// band self's body sweeps (lateral offset below the two radii), unless it faces self (its
/// heading has a negative component along `direction`: someone coming the other way is avoided,
/// not followed). `robot` (may be null) counts whatever its heading: it does not step aside. +inf
/// when there is none, or when `direction` is zero.
double Headway(const SocialAgent& self, const Vec2& direction, std::span<const SocialAgent> others,
               const SocialAgent* robot = nullptr);

/// The speed (m/s) the rule allows at `headway` (m) for someone whose free speed is
/// `desired_speed` (m/s): min(desired_speed, max(0, (headway - l) / T)); desired_speed when the
/// rule is disabled or the headway infinite.
double HeadwaySpeed(double headway, double desired_speed, const SpeedHeadwayConfig& config);

}  // namespace retrace::sim
