#include "bench/engine/stepper.hpp"

#include <utility>

namespace retrace::bench {
namespace {

constexpr double kProgressPeriod = 10.0;  // s of simulated time between progress reports

}  // namespace

Stepper::Stepper(sim::Simulator& simulator, double control_rate_hz, ProgressFn progress)
    : simulator_(simulator),
      control_steps_(
          sim::PeriodInSteps("nav.control_rate_hz", control_rate_hz, simulator.time_step())),
      control_dt_(static_cast<double>(control_steps_) * simulator.time_step()),
      progress_(std::move(progress)),
      next_report_(kProgressPeriod) {}

void Stepper::SetTap(SensorTap* tap) {
  tap_ = tap;
  if (tap_ != nullptr) {
    tap_->OnOdometry(simulator_.time(), simulator_.OdometryPose(), simulator_.RobotPose());
  }
}

sim::SimStep Stepper::Step(const core::Twist& command) {
  sim::SimStep s = simulator_.Step(command);
  ++steps_;
  collisions_.insert(collisions_.end(), s.collisions.begin(), s.collisions.end());
  if (tap_ != nullptr) {
    if (s.odometry) tap_->OnOdometry(s.time, simulator_.OdometryPose(), simulator_.RobotPose());
    if (s.lidar) tap_->OnScan(s.lidar->scan, simulator_.OdometryPose(), simulator_.RobotPose());
  }
  if (progress_ && s.time >= next_report_) {
    progress_(s.time);
    next_report_ += kProgressPeriod;
  }
  return s;
}

}  // namespace retrace::bench
