#pragma once
// A contact between the robot and something else, as recorded by the physics world.

#include <array>
#include <string_view>
#include <utility>

#include "core/config.hpp"
#include "core/pose2.hpp"

namespace retrace::sim {

/// What the robot touched.
enum class CollisionKind { kStatic, kPedestrian };

/// One contact that began between the robot and static geometry or a pedestrian.
struct CollisionEvent {
  /// Simulation time (s) at the start of the step in which Box2D reported the contact; the
  /// bodies began touching within one time step of it.
  double time = 0.0;
  CollisionKind kind = CollisionKind::kStatic;
  int pedestrian_id = -1;        ///< DynamicCircle id of the pedestrian; -1 for static
  core::Vec2 point_W{0.0, 0.0};  ///< contact point in the world frame W (m)
};

}  // namespace retrace::sim

template <>
struct retrace::core::EnumTraits<retrace::sim::CollisionKind> {
  static constexpr std::array<std::pair<retrace::sim::CollisionKind, std::string_view>, 2> kNames{
      {{retrace::sim::CollisionKind::kStatic, "static"},
       {retrace::sim::CollisionKind::kPedestrian, "pedestrian"}}};
};
