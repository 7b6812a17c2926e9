#pragma once
// How a pedestrian reacts to the robot, after HuNavSim's six behaviours (Pérez-Higueras,
// Otero, Caballero & Merino 2023, "HuNavSim: A ROS 2 Human Navigation Simulator for
// Benchmarking Human-Aware Robot Navigation", IEEE RA-L 8(11)):
//
//   regular      gives the robot the berth of the crowd model's robot term
//   impassive    ignores it as a social agent: keeps off it only as off a wall
//   surprised    stops when it comes near, for surprised_time, then goes on
//   curious      walks up to it and follows it at curious_gap for curious_time
//   scared       keeps a wider berth (scared_strength, scared_range) and, when it comes near,
//                walks away from it until it is notice_distance away again
//   threatening  steps into its path, threatening_gap in front of it, for threatening_time
//
// A reaction starts when the robot's edge comes within notice_distance of the person's; after one
// ends the person goes back to its route and does not react again for rest_time. The decisions
// are pure functions here; sim/pedestrians.cpp keeps each person's state.

#include <array>
#include <string_view>
#include <utility>

#include "core/config.hpp"
#include "core/pose2.hpp"

namespace retrace::sim {

enum class RobotBehaviour { kRegular, kImpassive, kSurprised, kCurious, kScared, kThreatening };

}  // namespace retrace::sim

template <>
struct retrace::core::EnumTraits<retrace::sim::RobotBehaviour> {
  static constexpr std::array<std::pair<retrace::sim::RobotBehaviour, std::string_view>, 6> kNames{
      {{retrace::sim::RobotBehaviour::kRegular, "regular"},
       {retrace::sim::RobotBehaviour::kImpassive, "impassive"},
       {retrace::sim::RobotBehaviour::kSurprised, "surprised"},
       {retrace::sim::RobotBehaviour::kCurious, "curious"},
       {retrace::sim::RobotBehaviour::kScared, "scared"},
       {retrace::sim::RobotBehaviour::kThreatening, "threatening"}}};
};

namespace retrace::sim {

using core::Vec2;

/// The behaviours' parameters, crowd-wide (which behaviour each person has is set per group).
struct RobotBehaviourConfig {
  double notice_distance = 3.0;   ///< m between the edges at which a reaction starts
  double surprised_time = 3.0;    ///< s a surprised person stands
  double curious_time = 15.0;     ///< s a curious person follows the robot
  double curious_gap = 0.8;       ///< m between the edges a curious person keeps
  double scared_strength = 24.0;  ///< robot repulsion V0 (m²/s²) for a scared person
  double scared_range = 1.0;      ///< its sigma (m)
  double threatening_time = 8.0;  ///< s a threatening person blocks the robot's way
  double threatening_gap = 0.4;   ///< m between the edges, in front of the robot
  double rest_time = 30.0;        ///< s after a reaction before the same person reacts again

  template <class V>
  void Reflect(V& v) {
    v("notice_distance", notice_distance);
    v("surprised_time", surprised_time);
    v("curious_time", curious_time);
    v("curious_gap", curious_gap);
    v("scared_strength", scared_strength);
    v("scared_range", scared_range);
    v("threatening_time", threatening_time);
    v("threatening_gap", threatening_gap);
    v("rest_time", rest_time);
  }
  /// Throws core::ConfigError naming the key: distances, times and gaps >= 0, notice_distance
  /// and scared_range > 0.
  void Validate() const;
};

/// True for the behaviours that react when the robot comes near (all but regular and
/// impassive, whose treatment of the robot never changes).
bool Reacts(RobotBehaviour behaviour);

/// How long (s) a reaction of `behaviour` lasts once it starts; scared lasts while the robot is
/// near (0 here).
double ReactionTime(RobotBehaviour behaviour, const RobotBehaviourConfig& config);

/// The robot as a disc in W: centre (m), radius (m), heading (unit vector) and velocity (m/s).
struct RobotDisc {
  Vec2 center{0.0, 0.0};
  double radius = 0.3;
  Vec2 heading{1.0, 0.0};
  Vec2 velocity{0.0, 0.0};
};

/// Where a reacting person goes (W, m) and at most how fast (m/s), for `person` at `position`
/// with `radius` (m) and free speed `desired_speed`: surprised stands (speed 0); curious makes for
/// the point curious_gap from the robot's edge on the person's side, slowing as it gets there;
/// scared walks straight away from the robot; threatening makes for the point threatening_gap in
/// front of the robot's edge along its heading. The point is `position` when standing.
struct ReactionTarget {
  Vec2 point{0.0, 0.0};
  double speed = 0.0;
};
ReactionTarget ReactionGoal(RobotBehaviour behaviour, const Vec2& position, double radius,
                            double desired_speed, const RobotDisc& robot,
                            const RobotBehaviourConfig& config);

}  // namespace retrace::sim
