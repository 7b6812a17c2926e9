#pragma once
// The robot as the navigation stack needs to know it: its footprint and where its LiDAR sits.
// It is one value, handed in by whoever runs the stack (the harness builds it from the
// scenario's `sim.robot` and `sim.lidar`), so that the simulated robot and the robot that nav
// plans for cannot disagree; no nav config key repeats it.

#include "core/pose2.hpp"

namespace retrace::nav {

struct RobotGeometry {
  double radius = 0.3;      ///< m, circular footprint
  core::Pose2 X_RL;         ///< the LiDAR frame L in the robot frame R (m, rad)
  double range_min = 0.05;  ///< m: readings below are not used
  double range_max = 30.0;  ///< m: the LiDAR's maximum range; the sensor models' z_max

  /// Throws core::ConfigError naming the field: radius > 0, 0 <= range_min < range_max, all
  /// finite.
  void Validate() const;
};

}  // namespace retrace::nav
