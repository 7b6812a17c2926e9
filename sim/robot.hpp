#pragma once
// The differential-drive robot plant: a circular body in the physics world that tracks (v, ω)
// commands within velocity and acceleration limits. The velocity set-point is slewed every
// physics step and set on the body; Box2D resolves contacts, so when the robot is blocked its
// actual motion (what the encoders measure) is whatever Box2D produced.

#include "core/config.hpp"
#include "core/pose2.hpp"
#include "core/twist.hpp"
#include "sim/physics_world.hpp"
#include "sim/static_geometry.hpp"

namespace retrace::sim {

/// Robot body and drive limits. Defaults describe a small indoor differential-drive base
/// (Pioneer/Kobuki class): 0.6 m diameter, walking speed at most, gentle accelerations.
struct RobotConfig {
  double radius = 0.3;             ///< m, circular footprint
  double max_speed = 1.0;          ///< m/s forward
  double max_reverse_speed = 0.2;  ///< m/s backwards (magnitude); teach-and-repeat rarely reverses
  double max_yaw_rate = 1.5;       ///< rad/s
  double max_accel = 1.0;          ///< m/s², forward and braking
  double max_yaw_accel = 3.0;      ///< rad/s²
  double mass = 30.0;              ///< kg, for contacts with pedestrians

  template <class V>
  void Reflect(V& v) {
    v("radius", radius);
    v("max_speed", max_speed);
    v("max_reverse_speed", max_reverse_speed);
    v("max_yaw_rate", max_yaw_rate);
    v("max_accel", max_accel);
    v("max_yaw_accel", max_yaw_accel);
    v("mass", mass);
  }
  /// Throws core::ConfigError naming the key: radius, max_speed, max_yaw_rate,
  /// max_accel, max_yaw_accel and mass must be > 0, max_reverse_speed >= 0.
  void Validate() const;
};

/// Clamps a command to the speed limits of `config`: v in [-max_reverse_speed, max_speed],
/// |omega| <= max_yaw_rate. Non-finite components become 0.
core::Twist ClampToLimits(const core::Twist& command, const RobotConfig& config);

/// One acceleration-limited step (dt s) of the set-point `current` towards `target`.
core::Twist SlewTowards(const core::Twist& current, const core::Twist& target,
                        const RobotConfig& config, double dt);

class Robot {
 public:
  /// Validates the config and adds the robot's body to `world` at X_WR, at rest.
  /// Throws core::ConfigError on an invalid config and core::WorldError if the footprint at
  /// X_WR overlaps static geometry or lies inside a solid.
  Robot(const RobotConfig& config, const StaticGeometry& geometry, const core::Pose2& X_WR,
        PhysicsWorld& world);

  const RobotConfig& config() const { return config_; }

  /// Latches a (v, ω) command in R (m/s, rad/s) until the next one (control rate).
  void SetCommand(const core::Twist& command) { command_ = command; }
  const core::Twist& command() const { return command_; }

  /// Clamps and slews the latched command by one physics step and sets the body's velocity.
  /// Call once before every PhysicsWorld::Step().
  void Actuate(PhysicsWorld& world);

  /// The velocity set-point the drive is tracking (after limits), in R.
  const core::Twist& setpoint() const { return setpoint_; }
  /// Ground-truth pose X_WR.
  core::Pose2 Pose(const PhysicsWorld& world) const { return world.RobotPose(); }

  /// Moves the robot to X_WR at rest and clears command and set-point (between runs).
  /// Throws core::WorldError like the constructor.
  void Reset(const StaticGeometry& geometry, const core::Pose2& X_WR, PhysicsWorld& world);

 private:
  RobotConfig config_;
  core::Twist command_;
  core::Twist setpoint_;
};

/// Throws core::WorldError if a circle of `radius` (m) at p_W overlaps static geometry or lies
/// inside a solid; `what` names the object in the message ("robot").
void RequireFootprintFree(const StaticGeometry& geometry, const core::Vec2& p_W, double radius,
                          const char* what);

}  // namespace retrace::sim
