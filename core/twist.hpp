#pragma once

#include "core/pose2.hpp"

namespace retrace::core {

/// A planar body velocity command or measurement in the robot frame R: forward speed v (m/s)
/// and yaw rate omega (rad/s).
struct Twist {
  double v = 0.0;
  double omega = 0.0;
  bool operator==(const Twist&) const = default;
};

/// One odometry increment in the robot frame, as integrated from the wheel encoders over one
/// odometry period: travelled distance (m) and heading change (rad) (paper eq. 2 inputs).
struct OdometryDelta {
  double distance = 0.0;
  double dtheta = 0.0;
};

/// Applies one odometry increment to a pose (paper eq. 2), integrated exactly along the arc:
/// the chord distance·sin(dθ/2)/(dθ/2) along the midpoint heading θ + dθ/2. The simulated
/// odometry and the navigation stack both integrate with this, so they agree to the bit.
Pose2 IntegrateOdometry(const Pose2& X_OR, const OdometryDelta& delta);

}  // namespace retrace::core
