#include "logs/ros1_messages.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "core/errors.hpp"
#include "logs/internal/ros_fields.hpp"
#include "logs/ros1_serialization.hpp"
#include "logs/ros_messages.hpp"

namespace retrace::logs {
namespace {

// The smallest serialized geometry_msgs/TransformStamped: seq and stamp (12), two string lengths
// (8), translation and rotation (56). A TFMessage's count is checked against it before allocating.
constexpr std::size_t kMinRos1TransformBytes = 76;

// ---- types: md5sums and definitions ----------------------------------------------------------

// The md5sums genmsg computes from the definitions (the same in every ROS 1 release since these
// messages last changed, before ROS Diamondback).
const std::map<std::string_view, std::string_view>& Md5Sums() {
  static const std::map<std::string_view, std::string_view> kMd5{
      {kRos1LaserScanType, "90c7ef2dc6895d81024acba2ac42f369"},
      {kRos1MultiEchoLaserScanType, "6fefb0c6da89d7c8abe4b339f5c2f8fb"},
      {kRos1OdometryType, "cd5e73d190d741a2f92e81eda573aca7"},
      {kRos1TfMessageType, "94810edda583a504dfda3829e70d7eec"},
      {kRos1LegacyTfMessageType, "94810edda583a504dfda3829e70d7eec"},
      {kRos1PoseStampedType, "d3812c3cbc69362b77dc0b19b345f8f5"},
      {kRos1PoseWithCovarianceStampedType, "953b798c0f514ff060a53a3498ce6246"},
  };
  return kMd5;
}

const internal::MessageDefinitions& Ros1Definitions() {
  static const internal::MessageDefinitions kDefinitions = internal::WithSharedGeometry({
      {"std_msgs/Header", {"uint32 seq\ntime stamp\nstring frame_id\n", {}}},
      {"geometry_msgs/Quaternion", {"float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n", {}}},
      {"geometry_msgs/TransformStamped",
       {"Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n",
        {"std_msgs/Header", "geometry_msgs/Transform"}}},
      {kRos1LaserScanType,
       {"Header header\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\n"
        "float32 time_increment\nfloat32 scan_time\nfloat32 range_min\nfloat32 range_max\n"
        "float32[] ranges\nfloat32[] intensities\n",
        {"std_msgs/Header"}}},
      {kRos1OdometryType,
       {"Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
        "geometry_msgs/TwistWithCovariance twist\n",
        {"std_msgs/Header", "geometry_msgs/PoseWithCovariance",
         "geometry_msgs/TwistWithCovariance"}}},
      {kRos1TfMessageType,
       {"geometry_msgs/TransformStamped[] transforms\n", {"geometry_msgs/TransformStamped"}}},
      {kRos1LegacyTfMessageType,
       {"geometry_msgs/TransformStamped[] transforms\n", {"geometry_msgs/TransformStamped"}}},
      {kRos1PoseStampedType,
       {"Header header\ngeometry_msgs/Pose pose\n", {"std_msgs/Header", "geometry_msgs/Pose"}}},
      {kRos1PoseWithCovarianceStampedType,
       {"Header header\ngeometry_msgs/PoseWithCovariance pose\n",
        {"std_msgs/Header", "geometry_msgs/PoseWithCovariance"}}},
      {"sensor_msgs/LaserEcho", {"float32[] echoes\n", {}}},
      {kRos1MultiEchoLaserScanType,
       {"Header header\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\n"
        "float32 time_increment\nfloat32 scan_time\nfloat32 range_min\nfloat32 range_max\n"
        "sensor_msgs/LaserEcho[] ranges\nsensor_msgs/LaserEcho[] intensities\n",
        {"std_msgs/Header", "sensor_msgs/LaserEcho"}}},
  });
  return kDefinitions;
}

// Runs `decode` on a reader over `data`, requiring it to use every byte, and prefixes any IoError
// with the type name.
template <typename Decode>
auto DecodeRos1As(std::string_view type, std::span<const std::uint8_t> data, Decode decode) {
  try {
    Ros1Reader r(data);
    auto message = decode(r);
    if (r.remaining() != 0) {
      throw core::IoError(std::to_string(r.remaining()) + " bytes after the last field (at byte " +
                          std::to_string(r.offset()) + ")");
    }
    return message;
  } catch (const core::IoError& e) {
    throw core::IoError(std::string(type) + ": " + e.what());
  }
}

// sensor_msgs/LaserEcho[]: the first echo of each, +inf for a beam without one.
std::vector<float> ReadFirstEchoes(Ros1Reader& r) {
  const std::uint32_t n = r.ReadSequenceLength(sizeof(std::uint32_t));
  std::vector<float> first(n, std::numeric_limits<float>::infinity());
  for (float& range : first) {
    const std::uint32_t echoes = r.ReadSequenceLength(sizeof(float));
    if (echoes == 0) continue;
    range = r.Read<float>();
    r.Skip(std::size_t{echoes - 1} * sizeof(float));
  }
  return first;
}

void SkipEchoes(Ros1Reader& r) {
  const std::uint32_t n = r.ReadSequenceLength(sizeof(std::uint32_t));
  for (std::uint32_t i = 0; i < n; ++i) r.SkipFloat32Sequence();
}

}  // namespace

namespace internal {

StampedFrame ReadHeader(Ros1Reader& r) {
  r.Read<std::uint32_t>();  // seq
  const double stamp = Ros1StampSeconds(r.ReadTime());
  return {stamp, r.ReadString()};
}

void WriteHeader(Ros1Writer& w, double stamp, std::string_view frame_id) {
  w.Write<std::uint32_t>(0);  // seq
  w.WriteTime(ToRos1Time(stamp));
  w.WriteString(frame_id);
}

}  // namespace internal

std::string_view Ros1TypeMd5(std::string_view type) {
  const auto it = Md5Sums().find(type);
  return it == Md5Sums().end() ? std::string_view() : it->second;
}

void RequireRos1Md5(std::string_view type, std::string_view md5sum) {
  const std::string_view known = Ros1TypeMd5(type);
  if (!known.empty() && md5sum == known) return;
  throw core::IoError(std::string(type) + ": md5sum '" + std::string(md5sum) +
                      "' is not the md5sum of the " + std::string(type) + " retrace reads (" +
                      std::string(known) + "): another definition of the type");
}

std::string_view Ros1MessageDefinition(std::string_view type) {
  static const std::map<std::string_view, std::string> kTexts = [] {
    std::map<std::string_view, std::string> texts;
    for (const auto& [name, md5] : Md5Sums())
      texts.emplace(name, internal::FullDefinition(Ros1Definitions(), name));
    return texts;
  }();
  const auto it = kTexts.find(type);
  return it == kTexts.end() ? std::string_view() : std::string_view(it->second);
}

ScanMessage DecodeRos1LaserScan(std::span<const std::uint8_t> data) {
  return DecodeRos1As(kRos1LaserScanType, data,
                      [](Ros1Reader& r) { return internal::ReadLaserScan(r); });
}

ScanMessage DecodeRos1MultiEchoLaserScan(std::span<const std::uint8_t> data) {
  return DecodeRos1As(kRos1MultiEchoLaserScanType, data, [](Ros1Reader& r) {
    ScanMessage m;
    const float angle_max = internal::ReadScanFields(r, m);
    m.scan.ranges = ReadFirstEchoes(r);
    SkipEchoes(r);  // intensities
    CheckScanGeometry(m, angle_max);
    return m;
  });
}

OdometryMessage DecodeRos1Odometry(std::span<const std::uint8_t> data) {
  return DecodeRos1As(kRos1OdometryType, data,
                      [](Ros1Reader& r) { return internal::ReadOdometry(r); });
}

TfMessage DecodeRos1TfMessage(std::span<const std::uint8_t> data, std::string_view type) {
  return DecodeRos1As(
      type, data, [](Ros1Reader& r) { return internal::ReadTfMessage(r, kMinRos1TransformBytes); });
}

PoseStampedMessage DecodeRos1PoseStamped(std::span<const std::uint8_t> data) {
  return DecodeRos1As(kRos1PoseStampedType, data,
                      [](Ros1Reader& r) { return internal::ReadPoseStamped(r); });
}

PoseStampedMessage DecodeRos1PoseWithCovarianceStamped(std::span<const std::uint8_t> data) {
  return DecodeRos1As(kRos1PoseWithCovarianceStampedType, data, [](Ros1Reader& r) {
    return internal::ReadPoseStamped(r, /*covariance=*/true);
  });
}

std::vector<std::uint8_t> EncodeRos1LaserScan(const ScanMessage& message) {
  Ros1Writer w;
  internal::WriteLaserScan(w, message);
  return w.Take();
}

std::vector<std::uint8_t> EncodeRos1Odometry(const OdometryMessage& message,
                                             const core::Twist& twist) {
  Ros1Writer w;
  internal::WriteOdometry(w, message, twist);
  return w.Take();
}

std::vector<std::uint8_t> EncodeRos1TfMessage(const TfMessage& message) {
  Ros1Writer w;
  internal::WriteTfMessage(w, message);
  return w.Take();
}

std::vector<std::uint8_t> EncodeRos1PoseStamped(const PoseStampedMessage& message) {
  Ros1Writer w;
  internal::WritePoseStamped(w, message);
  return w.Take();
}

}  // namespace retrace::logs
