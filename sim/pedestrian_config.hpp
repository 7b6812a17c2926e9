#pragma once
// Configuration of pedestrian groups, as listed in world files. Crowd-wide behaviour (social
// force, walk planner) is CrowdConfig in sim/pedestrians.hpp.

#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "core/config.hpp"
#include "core/pose2.hpp"
#include "sim/pedestrian_behaviour.hpp"

namespace retrace::sim {

enum class PedestrianMode { kWander, kLoop, kStand };

}  // namespace retrace::sim

template <>
struct retrace::core::EnumTraits<retrace::sim::PedestrianMode> {
  static constexpr std::array<std::pair<retrace::sim::PedestrianMode, std::string_view>, 3> kNames{
      {{retrace::sim::PedestrianMode::kWander, "wander"},
       {retrace::sim::PedestrianMode::kLoop, "loop"},
       {retrace::sim::PedestrianMode::kStand, "stand"}}};
};

namespace retrace::sim {

/// A group of pedestrians spawned at random free points of a region (W, m).
/// `wander`: each walks between random free points of the region.
/// `loop`: each follows the waypoint loop, starting at a random waypoint.
/// `stand`: each stands still where it spawned (people waiting, talking): a pedestrian to the
/// LiDAR and the collision metrics, an obstacle to the walkers; its speed is drawn but unused.
struct PedestrianGroupConfig {
  int count = 1;
  core::Vec2 region_min{0.0, 0.0};
  core::Vec2 region_max{1.0, 1.0};
  PedestrianMode mode = PedestrianMode::kWander;
  std::vector<core::Vec2> waypoints;
  double speed_mean = 1.34;  ///< desired speed (m/s), drawn per person
  double speed_std = 0.26;
  double radius = 0.3;  ///< m
  /// How the group's people react to the robot (sim/pedestrian_behaviour.hpp; a group of one
  /// sets one person's).
  RobotBehaviour behaviour = RobotBehaviour::kRegular;

  template <class V>
  void Reflect(V& v) {
    v("count", count);
    v("region_min", region_min);
    v("region_max", region_max);
    v("mode", mode);
    v("waypoints", waypoints);
    v("speed_mean", speed_mean);
    v("speed_std", speed_std);
    v("radius", radius);
    v("behaviour", behaviour);
  }
  void Validate() const;
};

}  // namespace retrace::sim
