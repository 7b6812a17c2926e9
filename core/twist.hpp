#pragma once

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

}  // namespace retrace::core
