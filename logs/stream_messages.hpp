#pragma once
// Which ROS messages feed a log's streams (docs/DESIGN.md §10), by their type in either ROS, and
// their decoding from either serialization: CDR messages (MCAP, rosbag2) by their ROS 2 names,
// ROS 1 messages (ROS 1 bags) by their ROS 1 names and md5sums.
//
//   stream     ROS 2 (CDR)                      ROS 1
//   ---------  -------------------------------  --------------------------------------------
//   scans      sensor_msgs/msg/LaserScan        sensor_msgs/LaserScan, MultiEchoLaserScan
//   odometry   nav_msgs/msg/Odometry            nav_msgs/Odometry
//   tf         tf2_msgs/msg/TFMessage           tf2_msgs/TFMessage, tf/tfMessage
//   poses      geometry_msgs/msg/PoseStamped    geometry_msgs/PoseStamped,
//                                               PoseWithCovarianceStamped

#include <string>
#include <string_view>

#include "logs/log_messages.hpp"
#include "logs/raw_message.hpp"

namespace retrace::logs {

/// The stream a message can feed.
enum class StreamKind { kNone, kScan, kOdometry, kTf, kPose };

/// The stream of a message of `type` in `encoding` ("cdr", "ros1"); kNone for any other type or
/// encoding (CARMEN lines included).
StreamKind StreamKindOf(std::string_view encoding, std::string_view type);
inline StreamKind StreamKindOf(const RawMessage& m) { return StreamKindOf(m.encoding, m.type); }

/// The types a stream is read from, for people: in ROS 2 names, or (`ros1`) in ROS 1 names, e.g.
/// "sensor_msgs/LaserScan or MultiEchoLaserScan".
std::string StreamTypeNames(StreamKind kind, bool ros1);

// The decoders of a message of each stream. A ROS 1 message's md5sum must be its type's
// (ros1_messages.hpp). They throw core::IoError "<type>: <reason>" for a malformed message, or
// for a message of another stream; the caller adds the file and the message.

ScanMessage DecodeStreamScan(const RawMessage& m);
OdometryMessage DecodeStreamOdometry(const RawMessage& m);
TfMessage DecodeStreamTf(const RawMessage& m);
/// PoseStamped, or the pose of a PoseWithCovarianceStamped.
PoseStampedMessage DecodeStreamPose(const RawMessage& m);

}  // namespace retrace::logs
