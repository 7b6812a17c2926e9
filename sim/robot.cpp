#include "sim/robot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/check.hpp"
#include "core/errors.hpp"

namespace retrace::sim {

void RobotConfig::Validate() const {
  core::RequirePositive("radius", radius);
  core::RequirePositive("max_speed", max_speed);
  core::RequireNonNegative("max_reverse_speed", max_reverse_speed);
  core::RequirePositive("max_yaw_rate", max_yaw_rate);
  core::RequirePositive("max_accel", max_accel);
  core::RequirePositive("max_yaw_accel", max_yaw_accel);
  core::RequirePositive("mass", mass);
}

core::Twist ClampToLimits(const core::Twist& command, const RobotConfig& config) {
  const double v = std::isfinite(command.v) ? command.v : 0.0;
  const double w = std::isfinite(command.omega) ? command.omega : 0.0;
  return {std::clamp(v, -config.max_reverse_speed, config.max_speed),
          std::clamp(w, -config.max_yaw_rate, config.max_yaw_rate)};
}

core::Twist SlewTowards(const core::Twist& current, const core::Twist& target,
                        const RobotConfig& config, double dt) {
  const double dv = config.max_accel * dt;
  const double dw = config.max_yaw_accel * dt;
  return {current.v + std::clamp(target.v - current.v, -dv, dv),
          current.omega + std::clamp(target.omega - current.omega, -dw, dw)};
}

void RequireFootprintFree(const StaticGeometry& geometry, const core::Vec2& p_W, double radius,
                          const char* what) {
  if (!std::isfinite(p_W.x()) || !std::isfinite(p_W.y())) {
    throw core::WorldError(std::string(what) + " position is not finite");
  }
  const bool inside = geometry.IsInside(p_W);
  const double clearance = geometry.Clearance(p_W);
  if (inside || clearance < radius) {
    char buf[256];
    std::snprintf(buf, sizeof(buf), "%s at (%.3f, %.3f) %s (clearance %.3f m < radius %.3f m)",
                  what, p_W.x(), p_W.y(), inside ? "is inside a solid" : "overlaps static geometry",
                  inside ? 0.0 : clearance, radius);
    throw core::WorldError(buf);
  }
}

Robot::Robot(const RobotConfig& config, const StaticGeometry& geometry, const core::Pose2& X_WR,
             PhysicsWorld& world)
    : config_(config) {
  config_.Validate();
  RequireFootprintFree(geometry, X_WR.translation(), config_.radius, "robot");
  world.AddRobot(X_WR, config_.radius, config_.mass);
}

void Robot::Actuate(PhysicsWorld& world) {
  setpoint_ = SlewTowards(setpoint_, ClampToLimits(command_, config_), config_, world.time_step());
  world.SetRobotVelocity(setpoint_);
}

void Robot::Reset(const StaticGeometry& geometry, const core::Pose2& X_WR, PhysicsWorld& world) {
  RequireFootprintFree(geometry, X_WR.translation(), config_.radius, "robot");
  world.TeleportRobot(X_WR);
  command_ = {};
  setpoint_ = {};
}

}  // namespace retrace::sim
