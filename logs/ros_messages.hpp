#pragma once
// The ROS 2 messages retrace reads and writes, decoded from and encoded to CDR
// (logs/cdr.hpp) independently of the container that holds them (MCAP or a rosbag2 SQLite
// database): sensor_msgs/msg/LaserScan, nav_msgs/msg/Odometry, tf2_msgs/msg/TFMessage and
// geometry_msgs/msg/PoseStamped, projected onto the plane (logs/log_messages.hpp), and their
// ros2msg definition texts for MCAP Schema records.
//
// Stamps: builtin_interfaces/Time {int32 sec, uint32 nanosec} is sec + nanosec·1e-9 seconds.
// Orientations: the yaw of the quaternion, z-y-x Euler angles as in io/tum.hpp.

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "core/twist.hpp"
#include "logs/log_messages.hpp"

namespace retrace::logs {

inline constexpr std::string_view kLaserScanType = "sensor_msgs/msg/LaserScan";
inline constexpr std::string_view kOdometryType = "nav_msgs/msg/Odometry";
inline constexpr std::string_view kTfMessageType = "tf2_msgs/msg/TFMessage";
inline constexpr std::string_view kPoseStampedType = "geometry_msgs/msg/PoseStamped";

/// builtin_interfaces/msg/Time.
struct RosTime {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
};

/// sec + nanosec·1e-9 (s).
double StampSeconds(RosTime t);

/// The nearest RosTime to `stamp` (s; nanosec in [0, 1e9)). Throws core::IoError for a
/// non-finite stamp or one outside the int32 seconds of builtin_interfaces/Time.
RosTime ToRosTime(double stamp);

/// The yaw (rad, in [-pi, pi)) of the rotation of quaternion (x, y, z, w), which need not be
/// unit: it is scaled by its largest component first, so huge components do not overflow.
/// Throws core::IoError for a non-finite component or a norm below 1e-9.
double YawFromQuaternion(double x, double y, double z, double w);

// The decoders take the serialized message with its 4-byte encapsulation header and throw
// core::IoError "<type>: <reason>" for a malformed one (truncated, a count beyond the buffer,
// a bad quaternion, ...); the caller adds the file and message index.

/// Beam i is at angle_min + i·angle_increment, as every ROS consumer reads it; angle_max is only
/// checked against angle_min + (n − 1)·angle_increment, since core::LaserScan keeps none. Up to
/// kAngleMaxSlackIncrements increments apart (real drivers are 1 or 2 off) the scan is used and
/// ScanMessage::angle_max says so (consistent to half an increment: empty); further apart it is
/// refused. NaN and ±inf ranges are kept as they are; intensities, time_increment and scan_time
/// are dropped.
ScanMessage DecodeLaserScan(std::span<const std::uint8_t> cdr);
/// How far (in increments) a LaserScan's angle_max may lie from angle_min + (n − 1)·increment.
inline constexpr double kAngleMaxSlackIncrements = 2.0;
/// The checks of DecodeLaserScan on a decoded scan of either ROS whose ranges, angle_min and
/// angle_increment are set: at most core::kMaxBeams beams, and the message's `angle_max` within
/// kAngleMaxSlackIncrements increments of the last beam's angle. Sets m.angle_max where it is
/// more than half an increment off. Throws core::IoError otherwise.
void CheckScanGeometry(ScanMessage& m, float angle_max);
/// angle_max = angle_min + (n − 1)·angle_increment; no intensities; time_increment and scan_time
/// 0. Throws core::IoError for a stamp ToRosTime refuses.
std::vector<std::uint8_t> EncodeLaserScan(const ScanMessage& message);

/// The pose of child_frame_id in frame_id; twist and covariances are read past.
OdometryMessage DecodeOdometry(std::span<const std::uint8_t> cdr);
/// With zero covariances and the given twist (linear.x = v, angular.z = omega, in the child
/// frame). Throws core::IoError for a stamp ToRosTime refuses.
std::vector<std::uint8_t> EncodeOdometry(const OdometryMessage& message,
                                         const core::Twist& twist = {});

TfMessage DecodeTfMessage(std::span<const std::uint8_t> cdr);
std::vector<std::uint8_t> EncodeTfMessage(const TfMessage& message);

PoseStampedMessage DecodePoseStamped(std::span<const std::uint8_t> cdr);
std::vector<std::uint8_t> EncodePoseStamped(const PoseStampedMessage& message);

/// The ros2msg definition of `type` (one of the four above) as rosbag2 stores it in an MCAP
/// Schema record: the type's fields, then for each type it depends on a line of 80 '=', a line
/// "MSG: pkg/Type" and that type's fields. Empty for any other type.
std::string_view RosMessageDefinition(std::string_view type);

}  // namespace retrace::logs
