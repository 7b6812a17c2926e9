#include "logs/stream_messages.hpp"

#include "core/errors.hpp"
#include "logs/ros1_messages.hpp"
#include "logs/ros_messages.hpp"

namespace retrace::logs {
namespace {

constexpr std::string_view kCdr = "cdr";
constexpr std::string_view kRos1 = "ros1";

StreamKind Ros1StreamKind(std::string_view type) {
  if (type == kRos1LaserScanType || type == kRos1MultiEchoLaserScanType) return StreamKind::kScan;
  if (type == kRos1OdometryType) return StreamKind::kOdometry;
  if (type == kRos1TfMessageType || type == kRos1LegacyTfMessageType) return StreamKind::kTf;
  if (type == kRos1PoseStampedType || type == kRos1PoseWithCovarianceStampedType) {
    return StreamKind::kPose;
  }
  return StreamKind::kNone;
}

StreamKind Ros2StreamKind(std::string_view type) {
  if (type == kLaserScanType) return StreamKind::kScan;
  if (type == kOdometryType) return StreamKind::kOdometry;
  if (type == kTfMessageType) return StreamKind::kTf;
  if (type == kPoseStampedType) return StreamKind::kPose;
  return StreamKind::kNone;
}

// A ROS 1 message of a known name must be the definition retrace reads.
bool IsRos1(const RawMessage& m) {
  if (m.encoding != kRos1) return false;
  RequireRos1Md5(m.type, m.md5sum);
  return true;
}

[[noreturn]] void NotOfStream(const RawMessage& m, std::string_view stream) {
  throw core::IoError(std::string(m.type) + ": not a message of the " + std::string(stream) +
                      " (encoding '" + std::string(m.encoding) + "')");
}

}  // namespace

StreamKind StreamKindOf(std::string_view encoding, std::string_view type) {
  if (encoding == kCdr) return Ros2StreamKind(type);
  if (encoding == kRos1) return Ros1StreamKind(type);
  return StreamKind::kNone;
}

std::string StreamTypeNames(StreamKind kind, bool ros1) {
  switch (kind) {
    case StreamKind::kScan:
      return ros1 ? "sensor_msgs/LaserScan or MultiEchoLaserScan" : std::string(kLaserScanType);
    case StreamKind::kOdometry:
      return ros1 ? std::string(kRos1OdometryType) : std::string(kOdometryType);
    case StreamKind::kTf:
      return ros1 ? "tf2_msgs/TFMessage or tf/tfMessage" : std::string(kTfMessageType);
    case StreamKind::kPose:
      return ros1 ? "geometry_msgs/PoseStamped or PoseWithCovarianceStamped"
                  : std::string(kPoseStampedType);
    case StreamKind::kNone:
      break;
  }
  return "";
}

ScanMessage DecodeStreamScan(const RawMessage& m) {
  if (StreamKindOf(m) != StreamKind::kScan) NotOfStream(m, "scans");
  if (!IsRos1(m)) return DecodeLaserScan(m.data);
  if (m.type == kRos1MultiEchoLaserScanType) return DecodeRos1MultiEchoLaserScan(m.data);
  return DecodeRos1LaserScan(m.data);
}

OdometryMessage DecodeStreamOdometry(const RawMessage& m) {
  if (StreamKindOf(m) != StreamKind::kOdometry) NotOfStream(m, "odometry");
  return IsRos1(m) ? DecodeRos1Odometry(m.data) : DecodeOdometry(m.data);
}

TfMessage DecodeStreamTf(const RawMessage& m) {
  if (StreamKindOf(m) != StreamKind::kTf) NotOfStream(m, "tf");
  return IsRos1(m) ? DecodeRos1TfMessage(m.data, m.type) : DecodeTfMessage(m.data);
}

PoseStampedMessage DecodeStreamPose(const RawMessage& m) {
  if (StreamKindOf(m) != StreamKind::kPose) NotOfStream(m, "poses");
  if (!IsRos1(m)) return DecodePoseStamped(m.data);
  if (m.type == kRos1PoseWithCovarianceStampedType) {
    return DecodeRos1PoseWithCovarianceStamped(m.data);
  }
  return DecodeRos1PoseStamped(m.data);
}

}  // namespace retrace::logs
