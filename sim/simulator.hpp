#pragma once
// The simulated world as one object: physics, robot plant, pedestrians, LiDAR and wheel
// odometry, advanced one fixed physics step at a time. It owns ground truth; the harness
// (bench) reads sensors from it and feeds commands into it, and may change the world between
// steps (scripted events: pedestrian groups and static obstacles added at run time). Sensors
// fire on integer multiples of the physics step (docs/DESIGN.md §3).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
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

  // --- Scripted events ---------------------------------------------------------------------
  // The harness changes the world between steps. Nothing here draws from the world's own
  // random streams, so a run without events is unchanged, and equal events at equal steps give
  // equal runs.

  /// Spawns a pedestrian group now, by the rules of the world's groups: random free points of
  /// its region, clear of static geometry (including added obstacles) by radius + planner
  /// margin, of other pedestrians by crowd.spawn_gap and of the robot by crowd.keep_clear_gap.
  /// They walk from the next step on, and are seen by the LiDAR and physics like the others.
  /// Randomness: the k-th call draws from the pedestrian stream split "runtime", then k.
  /// Returns their DynamicCircle ids. Throws core::ConfigError for an invalid group (key as in
  /// PedestrianGroupConfig, e.g. "count") and core::WorldError when they cannot be placed; then
  /// nothing is added.
  std::vector<int> AddPedestrians(const PedestrianGroupConfig& group);

  /// Adds a static obstacle now (W): solid for physics from the next step on (robot contacts are
  /// CollisionKind::kStatic events), seen by the LiDAR from the next scan (BeamTruth kStatic),
  /// counted by StaticClearance, repelling and re-routing pedestrians. Pedestrians it lands on
  /// are pushed out by the physics. Throws core::ConfigError for an invalid box or circle and
  /// core::WorldError (naming both positions) if it would overlap the robot's footprint; then
  /// nothing is added. Box2D keeps a 1 cm skin around static shapes, so an obstacle placed
  /// within 1 cm of the robot is a collision at the next step.
  void AddObstacle(const BoxConfig& box);
  void AddObstacle(const CircleConfig& circle);

  /// Distance (m) from p_W to the nearest static surface, world geometry or added obstacle; 0
  /// inside a solid. Brute force over all static primitives.
  double StaticClearance(const core::Vec2& p_W) const;

  double time() const { return physics_.time(); }
  double time_step() const { return physics_.time_step(); }
  const SimConfig& config() const { return config_; }
  /// The world file's static geometry (without the added obstacles).
  const StaticGeometry& geometry() const { return world_.geometry; }
  /// The obstacles added by AddObstacle, as polygons (boxes) and circles in W.
  const StaticGeometry& added_obstacles() const { return added_obstacles_; }
  /// Ground-truth robot pose X_WR.
  core::Pose2 RobotPose() const { return physics_.RobotPose(); }
  /// Actual robot twist in R (m/s, rad/s).
  core::Twist RobotTwist() const { return physics_.RobotTwist(); }
  /// The odometry's own pose estimate X_OR (identity at the start).
  const core::Pose2& OdometryPose() const { return odometry_.pose(); }
  /// Pedestrians as circles in W now.
  std::vector<DynamicCircle> PedestrianCircles() const { return physics_.PedestrianCircles(); }
  /// A pedestrian's velocity (W, m/s) by its DynamicCircle id.
  core::Vec2 PedestrianVelocity(int id) const { return physics_.PedestrianVelocity(id); }
  const Pedestrians& pedestrians() const { return *pedestrians_; }
  /// Every collision so far, in order.
  const std::vector<CollisionEvent>& collisions() const { return collisions_; }

 private:
  void RequireClearOfRobot(const StaticGeometry& solid, const std::string& what) const;
  void AddToSensorsAndCrowd(const StaticGeometry& solid);

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
  StaticGeometry added_obstacles_;
};

/// Number of physics steps in one period of a sensor running at rate_hz. Throws
/// core::ConfigError(key) unless the period is an integer multiple of the step.
std::uint64_t PeriodInSteps(const char* key, double rate_hz, double time_step);

}  // namespace retrace::sim
