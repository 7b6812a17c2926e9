#pragma once
// The messages retrace reads and writes, field by field, for both ROS wire formats: ROS 1
// serialization (logs/ros1_serialization.hpp) and ROS 2's CDR (logs/cdr.hpp). Their readers and
// writers share one vocabulary (Read<T>, ReadString, ReadSequenceLength, ReadFloat32Sequence,
// SkipFloat64Array, ...; CDR aligns inside them), and the messages differ between the two only in
// std_msgs/Header (ROS 1 has a seq; the stamp's types) and in the smallest size of a
// TransformStamped. logs/ros_messages.cpp and logs/ros1_messages.cpp instantiate these templates
// on their reader and writer, so both decode into the same structs (logs/log_messages.hpp)
// through the same code.
//
// Also the message definition texts both formats store beside their messages (MCAP Schema
// records, ROS 1 bag connection headers): a type's fields, then each type it depends on.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/pose2.hpp"
#include "core/twist.hpp"
#include "logs/cdr.hpp"
#include "logs/log_messages.hpp"
#include "logs/ros1_serialization.hpp"
#include "logs/ros_messages.hpp"

namespace retrace::logs::internal {

/// std_msgs/Header without ROS 1's seq: the stamp (s) and the frame.
struct StampedFrame {
  double stamp = 0.0;
  std::string frame_id;
};

// The header, in each format (defined beside its messages).
StampedFrame ReadHeader(CdrReader& r);
StampedFrame ReadHeader(Ros1Reader& r);
void WriteHeader(CdrWriter& w, double stamp, std::string_view frame_id);
void WriteHeader(Ros1Writer& w, double stamp, std::string_view frame_id);

/// geometry_msgs/Point (or Vector3) and Quaternion, projected onto the plane.
template <typename Reader>
core::Pose2 ReadPlanarPose(Reader& r) {
  std::array<double, 7> v;  // x, y, z, qx, qy, qz, qw
  for (double& value : v) value = r.template Read<double>();
  return core::Pose2(v[0], v[1], YawFromQuaternion(v[3], v[4], v[5], v[6]));
}

template <typename Writer>
void WritePlanarPose(Writer& w, const core::Pose2& pose) {
  w.WriteFloat64Array(std::array<double, 7>{
      pose.x, pose.y, 0.0, 0.0, 0.0, std::sin(0.5 * pose.theta), std::cos(0.5 * pose.theta)});
}

/// The fields of a LaserScan (or ROS 1 MultiEchoLaserScan) before its ranges, into `m`;
/// returns angle_max, for CheckScanGeometry once the ranges are read.
template <typename Reader>
float ReadScanFields(Reader& r, ScanMessage& m) {
  StampedFrame h = ReadHeader(r);
  m.scan.stamp = h.stamp;
  m.frame_id = std::move(h.frame_id);
  m.scan.angle_min = r.template Read<float>();
  const float angle_max = r.template Read<float>();
  m.scan.angle_increment = r.template Read<float>();
  r.template Read<float>();  // time_increment
  r.template Read<float>();  // scan_time
  m.scan.range_min = r.template Read<float>();
  m.scan.range_max = r.template Read<float>();
  return angle_max;
}

template <typename Reader>
ScanMessage ReadLaserScan(Reader& r) {
  ScanMessage m;
  const float angle_max = ReadScanFields(r, m);
  m.scan.ranges = r.ReadFloat32Sequence();
  r.SkipFloat32Sequence();  // intensities
  CheckScanGeometry(m, angle_max);
  return m;
}

/// angle_max = angle_min + (n − 1)·angle_increment; no intensities; time_increment and scan_time
/// 0.
template <typename Writer>
void WriteLaserScan(Writer& w, const ScanMessage& message) {
  const core::LaserScan& s = message.scan;
  WriteHeader(w, s.stamp, message.frame_id);
  const double angle_max = s.size() > 0 ? s.Angle(s.size() - 1) : s.angle_min;
  for (double v : std::array<double, 7>{s.angle_min, angle_max, s.angle_increment, 0.0, 0.0,
                                        s.range_min, s.range_max})
    w.template Write<float>(static_cast<float>(v));
  w.WriteFloat32Sequence(s.ranges);
  w.WriteFloat32Sequence({});  // intensities
}

/// The pose of child_frame_id in frame_id; the twist and the covariances are read past.
template <typename Reader>
OdometryMessage ReadOdometry(Reader& r) {
  OdometryMessage m;
  StampedFrame h = ReadHeader(r);
  m.stamp = h.stamp;
  m.frame_id = std::move(h.frame_id);
  m.child_frame_id = r.ReadString();
  m.pose = ReadPlanarPose(r);
  r.SkipFloat64Array(36 + 6 + 36);  // pose covariance, twist (linear, angular), twist covariance
  return m;
}

/// With zero covariances and the twist (linear.x = v, angular.z = omega, in the child frame).
template <typename Writer>
void WriteOdometry(Writer& w, const OdometryMessage& message, const core::Twist& twist) {
  static const std::array<double, 36> kZeroCovariance{};
  WriteHeader(w, message.stamp, message.frame_id);
  w.WriteString(message.child_frame_id);
  WritePlanarPose(w, message.pose);
  w.WriteFloat64Array(kZeroCovariance);
  w.WriteFloat64Array(std::array<double, 6>{twist.v, 0.0, 0.0, 0.0, 0.0, twist.omega});
  w.WriteFloat64Array(kZeroCovariance);
}

/// `min_transform_bytes`: the smallest serialized TransformStamped, which the count is checked
/// against before anything is allocated.
template <typename Reader>
TfMessage ReadTfMessage(Reader& r, std::size_t min_transform_bytes) {
  TfMessage m;
  const std::uint32_t n = r.ReadSequenceLength(min_transform_bytes);
  m.transforms.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    TransformMessage t;
    StampedFrame h = ReadHeader(r);
    t.stamp = h.stamp;
    t.parent = std::move(h.frame_id);
    t.child = r.ReadString();
    t.X_PC = ReadPlanarPose(r);
    m.transforms.push_back(std::move(t));
  }
  return m;
}

template <typename Writer>
void WriteTfMessage(Writer& w, const TfMessage& message) {
  w.WriteSequenceLength(static_cast<std::uint32_t>(message.transforms.size()));
  for (const TransformMessage& t : message.transforms) {
    WriteHeader(w, t.stamp, t.parent);
    w.WriteString(t.child);
    WritePlanarPose(w, t.X_PC);
  }
}

/// geometry_msgs/PoseStamped, or with `covariance` PoseWithCovarianceStamped (its covariance read
/// past).
template <typename Reader>
PoseStampedMessage ReadPoseStamped(Reader& r, bool covariance = false) {
  PoseStampedMessage m;
  StampedFrame h = ReadHeader(r);
  m.stamp = h.stamp;
  m.frame_id = std::move(h.frame_id);
  m.pose = ReadPlanarPose(r);
  if (covariance) r.SkipFloat64Array(36);
  return m;
}

template <typename Writer>
void WritePoseStamped(Writer& w, const PoseStampedMessage& message) {
  WriteHeader(w, message.stamp, message.frame_id);
  WritePlanarPose(w, message.pose);
}

/// A message type's definition: one "type name" line per field, and the "pkg/Type" names its
/// fields use.
struct MessageDefinition {
  std::string_view fields;
  std::vector<std::string_view> depends;
};
using MessageDefinitions = std::map<std::string_view, MessageDefinition>;

/// `own` and the geometry_msgs types whose definitions ROS 1 and ROS 2 share (Point, Vector3,
/// Pose, PoseWithCovariance, Twist, TwistWithCovariance, Transform).
MessageDefinitions WithSharedGeometry(MessageDefinitions own);

/// The full definition text of `name` as ROS tools store it: its fields, then for each type it
/// depends on (depth first, in order of first use) a line of 80 '=', a line "MSG: pkg/Type" and
/// that type's fields.
std::string FullDefinition(const MessageDefinitions& definitions, std::string_view name);

}  // namespace retrace::logs::internal
