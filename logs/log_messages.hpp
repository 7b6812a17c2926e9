#pragma once
// The decoded messages retrace reads from logs, in core types. 3D poses are projected onto
// the plane: x, y and the yaw of the quaternion (z, roll and pitch are dropped).

#include <optional>
#include <string>
#include <vector>

#include "core/laser_scan.hpp"
#include "core/pose2.hpp"

namespace retrace::logs {

/// sensor_msgs/msg/LaserScan (or a CARMEN laser line's scan): the scan in its own frame.
struct ScanMessage {
  core::LaserScan scan;  ///< scan.stamp is the header stamp (s since the epoch)
  std::string frame_id;  ///< the laser's frame
  /// The message's angle_max (rad) where it is more than half an increment from the last beam's
  /// angle_min + (n − 1)·angle_increment (a driver's quirk; the beams are placed by angle_min and
  /// the increment all the same); empty where they agree.
  std::optional<double> angle_max = std::nullopt;
};

/// nav_msgs/msg/Odometry: the pose of child_frame_id (the robot base) in frame_id (odom).
struct OdometryMessage {
  double stamp = 0.0;  ///< s since the epoch
  std::string frame_id;
  std::string child_frame_id;
  core::Pose2 pose;
};

/// One geometry_msgs/msg/TransformStamped: X_{parent child}.
struct TransformMessage {
  double stamp = 0.0;
  std::string parent;
  std::string child;
  core::Pose2 X_PC;
};

/// tf2_msgs/msg/TFMessage.
struct TfMessage {
  std::vector<TransformMessage> transforms;
};

/// geometry_msgs/msg/PoseStamped: a pose of the robot in frame_id.
struct PoseStampedMessage {
  double stamp = 0.0;
  std::string frame_id;
  core::Pose2 pose;
};

}  // namespace retrace::logs
