#pragma once
// The rigid-body world (Box2D 2.4 behind a pimpl): static geometry as one static body of
// two-sided edges and circles (plus solid boxes and circles added at run time), the robot and
// the pedestrians as dynamic circles, advanced with a fixed time step. Contacts that begin
// between the robot and anything else are recorded as CollisionEvents. Bodies are driven
// kinematically through their velocities; Box2D resolves contacts, so nothing passes through
// walls or through each other. Static shapes carry Box2D's 1 cm skin (b2_polygonRadius), so
// bodies rest about 1 cm outside the geometry; moving bodies may overlap each other by a
// centimetre or two for a step (Box2D's contact tolerance).

#include <cstdint>
#include <memory>
#include <vector>

#include "core/config.hpp"
#include "core/pose2.hpp"
#include "core/twist.hpp"
#include "sim/collision_event.hpp"
#include "sim/static_geometry.hpp"

namespace retrace::sim {

/// Fixed-step integration settings.
struct PhysicsConfig {
  double time_step = 0.01;      ///< s; sensors and controllers run on multiples of it
  int velocity_iterations = 8;  ///< Box2D solver iterations (Box2D's recommended values)
  int position_iterations = 3;

  template <class V>
  void Reflect(V& v) {
    v("time_step", time_step);
    v("velocity_iterations", velocity_iterations);
    v("position_iterations", position_iterations);
  }
  /// Throws core::ConfigError naming the key: time_step in (0, 0.1], iterations in [1, 100].
  void Validate() const;
};

class PhysicsWorld {
 public:
  /// Builds the static body from `geometry` (every segment as a two-sided edge, every circle
  /// as a circle); the geometry is not referenced afterwards. Throws core::ConfigError on an
  /// invalid config.
  explicit PhysicsWorld(const StaticGeometry& geometry, const PhysicsConfig& config = {});
  ~PhysicsWorld();
  PhysicsWorld(PhysicsWorld&&) noexcept;
  PhysicsWorld& operator=(PhysicsWorld&&) noexcept;
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  const PhysicsConfig& config() const;
  double time_step() const;
  /// Simulation time (s): number of steps taken times the time step.
  double time() const;
  std::uint64_t step_count() const;

  /// Advances the world by one time step and records the robot's new contacts.
  void Step();

  // --- Obstacles added at run time ----------------------------------------------------------
  /// Adds a solid box (centre and yaw X_WB, full extents `size` along B's x and y, m) to the
  /// static geometry now: bodies collide with it from the next step on, robot contacts with it
  /// are kStatic events. Solid (not edges), so a body it was dropped on is pushed out rather
  /// than trapped inside. Size must be positive and the pose finite (checked).
  void AddStaticBox(const core::Pose2& X_WB, const core::Vec2& size);
  /// Adds a solid circle (W, m) to the static geometry now, like AddStaticBox.
  void AddStaticCircle(const Circle& circle);

  // --- Robot -------------------------------------------------------------------------------
  /// Adds the robot as a dynamic circle (radius m, mass kg) at X_WR, at rest, with continuous
  /// collision against pedestrians as well as static geometry. At most one robot; radius and
  /// mass must be positive (internal invariants; Robot validates its config first).
  void AddRobot(const core::Pose2& X_WR, double radius, double mass);
  bool has_robot() const;
  double robot_radius() const;
  /// Ground-truth robot pose X_WR.
  core::Pose2 RobotPose() const;
  /// Actual body twist in the robot frame R: forward speed (m/s, the component of the body's
  /// linear velocity along its heading) and yaw rate (rad/s).
  core::Twist RobotTwist() const;
  /// Actual linear velocity of the robot's centre in W (m/s), including any sideways slip.
  core::Vec2 RobotVelocityW() const;
  /// Sets the body velocity for the next step: v (m/s) along the current heading, omega (rad/s).
  void SetRobotVelocity(const core::Twist& twist_R);
  /// Moves the robot to X_WR at rest (between runs). Overlaps are resolved by the next steps.
  void TeleportRobot(const core::Pose2& X_WR);

  // --- Pedestrians -------------------------------------------------------------------------
  /// Adds a pedestrian as a dynamic circle (non-rotating) at p_W (m) with radius (m) and
  /// mass (kg), at rest. Returns its id: 0, 1, 2, ... in order of addition.
  int AddPedestrian(const core::Vec2& p_W, double radius, double mass);
  core::Vec2 PedestrianPosition(int id) const;  ///< W, m
  core::Vec2 PedestrianVelocity(int id) const;  ///< W, m/s
  /// Sets a pedestrian's linear velocity in W (m/s) for the next step.
  void SetPedestrianVelocity(int id, const core::Vec2& v_W);
  /// All pedestrians as circles in W at the current time (id = pedestrian id).
  std::vector<DynamicCircle> PedestrianCircles() const;

  // --- Collisions --------------------------------------------------------------------------
  /// Returns the collision events recorded since the last call and forgets them.
  std::vector<CollisionEvent> TakeCollisions();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace retrace::sim
