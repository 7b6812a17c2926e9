#include "sim/simulator.hpp"

#include <cmath>

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

}  // namespace retrace::sim
