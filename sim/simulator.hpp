#pragma once
// The simulated world as one object: physics, robot plant, pedestrians, LiDAR and wheel
// odometry, advanced one fixed physics step at a time. It owns ground truth; the harness
// (bench) reads sensors from it and feeds commands into it. Sensors fire on integer multiples
// of the physics step (DESIGN §3).

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/config.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "core/twist.hpp"
#include "sim/collision_event.hpp"
#include "sim/lidar.hpp"
#include "sim/odometry.hpp"
#include "sim/pedestrians.hpp"
#include "sim/physics_world.hpp"
#include "sim/robot.hpp"
#include "sim/world_file.hpp"

namespace retrace::sim {

/// Everything about the simulated robot and its sensors (the world comes from a world file).
struct SimConfig {
  PhysicsConfig physics;
  RobotConfig robot;
  LidarConfig lidar;
  OdometryConfig odometry;
  CrowdConfig crowd;
  template <class V>
  void Reflect(V& v) {
    v("physics", physics);
    v("robot", robot);
    v("lidar", lidar);
    v("odometry", odometry);
    v("crowd", crowd);
  }
  /// Throws core::ConfigError naming the key, also when a sensor period is not an integer
  /// multiple of the physics time step.
  void Validate() const;
};

/// What one physics step produced: sensor data that came due, and new collisions.
struct SimStep {
  double time = 0.0;  ///< simulation time after the step (s)
  std::optional<LidarReading> lidar;
  std::optional<core::OdometryDelta> odometry;
  std::vector<CollisionEvent> collisions;
};

class Simulator {
 public:
  /// Builds the world, places the robot at X_WR_start and spawns the pedestrians clear of it.
  /// `world` must outlive the simulator. Randomness is split from `rng` per component
  /// ("lidar", "odometry", "pedestrians"). Throws core::ConfigError on an invalid config and
  /// core::WorldError if the robot starts inside or against an obstacle, or pedestrians
  /// cannot be placed.
  Simulator(const World& world, const SimConfig& config, const core::Pose2& X_WR_start,
            const core::Rng& rng);
  ~Simulator();
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  /// Latches the (v, ω) command (R, m/s and rad/s), advances pedestrians, robot and physics by
  /// one step, then samples the sensors that are due at the new time.
  SimStep Step(const core::Twist& command);

  double time() const { return physics_.time(); }
  double time_step() const { return physics_.time_step(); }
  const SimConfig& config() const { return config_; }
  const StaticGeometry& geometry() const { return world_.geometry; }
  /// Ground-truth robot pose X_WR.
  core::Pose2 RobotPose() const { return physics_.RobotPose(); }
  /// Actual robot twist in R (m/s, rad/s).
  core::Twist RobotTwist() const { return physics_.RobotTwist(); }
  /// The odometry's own pose estimate X_OR (identity at the start).
  const core::Pose2& OdometryPose() const { return odometry_.pose(); }
  /// Pedestrians as circles in W now.
  std::vector<DynamicCircle> PedestrianCircles() const { return physics_.PedestrianCircles(); }
  const Pedestrians& pedestrians() const { return *pedestrians_; }
  /// Every collision so far, in order.
  const std::vector<CollisionEvent>& collisions() const { return collisions_; }

 private:
  const World& world_;
  SimConfig config_;
  PhysicsWorld physics_;
  Robot robot_;
  std::unique_ptr<Pedestrians> pedestrians_;
  Lidar lidar_;
  Odometry odometry_;
  core::Rng lidar_rng_;
  std::uint64_t lidar_period_steps_;
  std::uint64_t odometry_period_steps_;
  core::Pose2 X_WR_last_odometry_;
  std::vector<CollisionEvent> collisions_;
};

/// Number of physics steps in one period of a sensor running at rate_hz. Throws
/// core::ConfigError(key) unless the period is an integer multiple of the step.
std::uint64_t PeriodInSteps(const char* key, double rate_hz, double time_step);

}  // namespace retrace::sim
