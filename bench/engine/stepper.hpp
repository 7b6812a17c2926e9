#pragma once
// The stepping that every episode loop shares (the teaching drive and the playback run): one
// physics step per call, which instants are control ticks of the navigation rate, the robot's
// contacts collected, progress reported every 10 s of simulated time.

#include <cstdint>
#include <vector>

#include "bench/engine/progress.hpp"
#include "bench/engine/sensor_tap.hpp"
#include "core/twist.hpp"
#include "sim/collision_event.hpp"
#include "sim/simulator.hpp"

namespace retrace::bench {

class Stepper {
 public:
  /// Steps `simulator` (which must outlive this object). Throws core::ConfigError naming
  /// nav.control_rate_hz when the control period is not a whole number of physics steps.
  Stepper(sim::Simulator& simulator, double control_rate_hz, ProgressFn progress = {});

  /// One physics step with `command` (and the sensors that came due, which go to the tap).
  sim::SimStep Step(const core::Twist& command);
  /// Copies every odometry tick and scan to `tap` (nullptr: none), which must outlive the steps.
  /// Hands every odometry tick and scan to `tap` from now on, starting with the odometry pose at
  /// this instant (the drive's start, where the odometry reads the identity), so that a log
  /// holds the increment of the first tick too.
  void SetTap(SensorTap* tap);

  /// Whether the current instant is a control tick: every control period, the start included.
  bool ControlDue() const { return steps_ % control_steps_ == 0; }
  /// s between control ticks.
  double control_dt() const { return control_dt_; }
  /// The robot's contacts so far, in time order.
  const std::vector<sim::CollisionEvent>& collisions() const { return collisions_; }

 private:
  sim::Simulator& simulator_;
  std::uint64_t control_steps_;
  double control_dt_;
  ProgressFn progress_;
  double next_report_;
  std::uint64_t steps_ = 0;
  std::vector<sim::CollisionEvent> collisions_;
  SensorTap* tap_ = nullptr;
};

}  // namespace retrace::bench
