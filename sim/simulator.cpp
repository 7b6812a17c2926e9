#include "sim/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/errors.hpp"

namespace retrace::sim {

std::uint64_t PeriodInSteps(const char* key, double rate_hz, double time_step) {
  const double steps = 1.0 / (rate_hz * time_step);
  const double rounded = std::round(steps);
  if (rounded < 1.0 || std::abs(steps - rounded) > 1e-6 * rounded) {
    throw core::ConfigError(key, "the period 1/" + core::FormatNumber(rate_hz) +
                                     " s must be an integer multiple of physics.time_step " +
                                     core::FormatNumber(time_step) + " s");
  }
  return static_cast<std::uint64_t>(rounded);
}

void SimConfig::Validate() const {
  physics.Validate();
  PeriodInSteps("lidar.rate_hz", lidar.rate_hz, physics.time_step);
  PeriodInSteps("odometry.rate_hz", odometry.rate_hz, physics.time_step);
}

Simulator::Simulator(const World& world, const SimConfig& config, const core::Pose2& X_WR_start,
                     const core::Rng& rng)
    : world_(world),
      config_(config),
      physics_(world.geometry, config.physics),
      robot_(config.robot, world.geometry, X_WR_start, physics_),
      lidar_(config.lidar, world.geometry),
      odometry_(config.odometry, rng.Split("odometry")),
      lidar_rng_(rng.Split("lidar")),
      lidar_period_steps_(PeriodInSteps("lidar.rate_hz", config.lidar.rate_hz, config.physics.time_step)),
      odometry_period_steps_(
          PeriodInSteps("odometry.rate_hz", config.odometry.rate_hz, config.physics.time_step)),
      X_WR_last_odometry_(X_WR_start) {
  config_.Validate();
  pedestrians_ = std::make_unique<Pedestrians>(
      world.config.pedestrians, config.crowd, world.geometry, rng.Split("pedestrians"),
      std::vector<Circle>{{X_WR_start.translation(), config.robot.radius}}, physics_);
}

Simulator::~Simulator() = default;

SimStep Simulator::Step(const core::Twist& command) {
  robot_.SetCommand(command);
  pedestrians_->Update(physics_);
  robot_.Actuate(physics_);
  physics_.Step();

  SimStep out;
  out.time = physics_.time();
  out.collisions = physics_.TakeCollisions();
  collisions_.insert(collisions_.end(), out.collisions.begin(), out.collisions.end());
  const std::uint64_t k = physics_.step_count();
  const core::Pose2 X_WR = physics_.RobotPose();
  if (k % odometry_period_steps_ == 0) {
    out.odometry = odometry_.Update(X_WR_last_odometry_, X_WR);
    X_WR_last_odometry_ = X_WR;
  }
  if (k % lidar_period_steps_ == 0) {
    const std::vector<DynamicCircle> people = physics_.PedestrianCircles();
    out.lidar = lidar_.Scan(X_WR, people, out.time, lidar_rng_);
  }
  return out;
}

std::vector<int> Simulator::AddPedestrians(const PedestrianGroupConfig& group) {
  const std::vector<Circle> keep_clear{{physics_.RobotPose().translation(), config_.robot.radius}};
  return pedestrians_->AddGroup(group, keep_clear, physics_);
}

void Simulator::AddObstacle(const BoxConfig& box) {
  box.Validate();
  StaticGeometry solid;
  solid.AddPolygon(BoxRing(box));
  char what[160];
  std::snprintf(what, sizeof(what), "obstacle box at (%.3f, %.3f) of %.3f m x %.3f m, yaw %.3f rad",
                box.center.x(), box.center.y(), box.size.x(), box.size.y(), box.yaw);
  RequireClearOfRobot(solid, what);
  physics_.AddStaticBox(core::Pose2(box.center.x(), box.center.y(), box.yaw), box.size);
  AddToSensorsAndCrowd(solid);
}

void Simulator::AddObstacle(const CircleConfig& circle) {
  circle.Validate();
  StaticGeometry solid;
  solid.AddCircle({circle.center, circle.radius});
  char what[160];
  std::snprintf(what, sizeof(what), "obstacle circle at (%.3f, %.3f) of radius %.3f m",
                circle.center.x(), circle.center.y(), circle.radius);
  RequireClearOfRobot(solid, what);
  physics_.AddStaticCircle({circle.center, circle.radius});
  AddToSensorsAndCrowd(solid);
}

void Simulator::RequireClearOfRobot(const StaticGeometry& solid, const std::string& what) const {
  // The same rule as for the robot's start (RequireFootprintFree): the footprint must not
  // overlap the solid; touching is allowed.
  const core::Vec2 p = physics_.RobotPose().translation();
  const double radius = config_.robot.radius;
  const double clearance = solid.Clearance(p);
  if (clearance < radius) {
    char buf[400];
    std::snprintf(buf, sizeof(buf),
                  "%s would overlap the robot at (%.3f, %.3f) at t = %.2f s (%s; clearance %.3f m "
                  "< robot radius %.3f m)",
                  what.c_str(), p.x(), p.y(), physics_.time(),
                  solid.IsInside(p) ? "it covers the robot's centre" : "too close", clearance,
                  radius);
    throw core::WorldError(buf);
  }
}

void Simulator::AddToSensorsAndCrowd(const StaticGeometry& solid) {
  lidar_.AddObstacles(solid);
  pedestrians_->AddObstacles(solid, physics_);
  for (const auto& ring : solid.polygons()) added_obstacles_.AddPolygon(ring);
  for (const Circle& c : solid.circles()) added_obstacles_.AddCircle(c);
}

double Simulator::StaticClearance(const core::Vec2& p_W) const {
  const double world = world_.geometry.Clearance(p_W);
  return added_obstacles_.empty() ? world : std::min(world, added_obstacles_.Clearance(p_W));
}

}  // namespace retrace::sim
