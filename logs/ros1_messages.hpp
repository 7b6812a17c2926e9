#pragma once
// The ROS 1 messages retrace reads and writes, in ROS 1 serialization (logs/ros1_serialization.hpp)
// as ROS 1 bags hold them, projected onto the plane like their ROS 2 twins (logs/ros_messages.hpp):
//
//   read and written   sensor_msgs/LaserScan, nav_msgs/Odometry, tf2_msgs/TFMessage,
//                      geometry_msgs/PoseStamped
//   read               sensor_msgs/MultiEchoLaserScan (the first echo of each beam),
//                      tf/tfMessage (tf2_msgs/TFMessage's layout under the old tf package's name),
//                      geometry_msgs/PoseWithCovarianceStamped (the pose; the covariance is
//                      read past)
//
// A ROS 1 type is known by its name and the md5sum of its definition, which every connection of a
// bag states: a type of a known name with another md5sum is another definition (an old or a
// patched message package) and is refused, never guessed at.
// Stamps: ROS 1 time {uint32 sec, uint32 nsec} is sec + nsec·1e-9 seconds.

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "core/twist.hpp"
#include "logs/log_messages.hpp"

namespace retrace::logs {

inline constexpr std::string_view kRos1LaserScanType = "sensor_msgs/LaserScan";
inline constexpr std::string_view kRos1MultiEchoLaserScanType = "sensor_msgs/MultiEchoLaserScan";
inline constexpr std::string_view kRos1OdometryType = "nav_msgs/Odometry";
inline constexpr std::string_view kRos1TfMessageType = "tf2_msgs/TFMessage";
inline constexpr std::string_view kRos1LegacyTfMessageType = "tf/tfMessage";
inline constexpr std::string_view kRos1PoseStampedType = "geometry_msgs/PoseStamped";
inline constexpr std::string_view kRos1PoseWithCovarianceStampedType =
    "geometry_msgs/PoseWithCovarianceStamped";

/// The md5sum of the definition of `type`, one of the seven types above, as roscpp and genpy
/// compute it (32 lowercase hex digits); empty for any other type.
std::string_view Ros1TypeMd5(std::string_view type);

/// Throws core::IoError "<type>: md5sum <md5sum> is not ..." unless `md5sum` is Ros1TypeMd5(type).
void RequireRos1Md5(std::string_view type, std::string_view md5sum);

/// The message definition of `type` as a bag's connection header holds it (its fields, then for
/// each type it depends on a line of 80 '=', a line "MSG: pkg/Type" and that type's fields), for
/// the seven types above; empty for any other type.
std::string_view Ros1MessageDefinition(std::string_view type);

// The decoders take the serialized message and throw core::IoError "<type>: <reason>" for a
// malformed one (truncated, a count beyond the buffer, a bad quaternion, trailing bytes, ...);
// the caller adds the file and the message. The header's seq is read past.

/// As DecodeLaserScan (logs/ros_messages.hpp): the same checks of the angles, the same fields.
ScanMessage DecodeRos1LaserScan(std::span<const std::uint8_t> data);
/// The first echo of each beam as its range (a beam without echoes: +inf, no return), the rest as
/// DecodeRos1LaserScan.
ScanMessage DecodeRos1MultiEchoLaserScan(std::span<const std::uint8_t> data);
OdometryMessage DecodeRos1Odometry(std::span<const std::uint8_t> data);
/// tf2_msgs/TFMessage and tf/tfMessage (one layout; `type` names it in errors).
TfMessage DecodeRos1TfMessage(std::span<const std::uint8_t> data,
                              std::string_view type = kRos1TfMessageType);
PoseStampedMessage DecodeRos1PoseStamped(std::span<const std::uint8_t> data);
/// The pose of a geometry_msgs/PoseWithCovarianceStamped (an amcl_pose, say).
PoseStampedMessage DecodeRos1PoseWithCovarianceStamped(std::span<const std::uint8_t> data);

// The encoders write seq 0 and throw core::IoError for a stamp ToRos1Time refuses.

/// angle_max = angle_min + (n − 1)·angle_increment; no intensities; time_increment and scan_time 0.
std::vector<std::uint8_t> EncodeRos1LaserScan(const ScanMessage& message);
/// With zero covariances and the given twist (linear.x = v, angular.z = omega, in the child frame).
std::vector<std::uint8_t> EncodeRos1Odometry(const OdometryMessage& message,
                                             const core::Twist& twist = {});
/// A tf2_msgs/TFMessage.
std::vector<std::uint8_t> EncodeRos1TfMessage(const TfMessage& message);
std::vector<std::uint8_t> EncodeRos1PoseStamped(const PoseStampedMessage& message);

}  // namespace retrace::logs
