#include "logs/ros1_messages.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "core/errors.hpp"
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

struct Ros1Definition {
  std::string_view fields;                // one "type name" line per field
  std::vector<std::string_view> depends;  // the "pkg/Type" names its fields use
};

const std::map<std::string_view, Ros1Definition>& Ros1Definitions() {
  static const std::map<std::string_view, Ros1Definition> kDefinitions{
      {"std_msgs/Header", {"uint32 seq\ntime stamp\nstring frame_id\n", {}}},
      {"geometry_msgs/Point", {"float64 x\nfloat64 y\nfloat64 z\n", {}}},
      {"geometry_msgs/Vector3", {"float64 x\nfloat64 y\nfloat64 z\n", {}}},
      {"geometry_msgs/Quaternion", {"float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n", {}}},
      {"geometry_msgs/Pose",
       {"geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n",
        {"geometry_msgs/Point", "geometry_msgs/Quaternion"}}},
      {"geometry_msgs/PoseWithCovariance",
       {"geometry_msgs/Pose pose\nfloat64[36] covariance\n", {"geometry_msgs/Pose"}}},
      {"geometry_msgs/Twist",
       {"geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n",
        {"geometry_msgs/Vector3"}}},
      {"geometry_msgs/TwistWithCovariance",
       {"geometry_msgs/Twist twist\nfloat64[36] covariance\n", {"geometry_msgs/Twist"}}},
      {"geometry_msgs/Transform",
       {"geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n",
        {"geometry_msgs/Vector3", "geometry_msgs/Quaternion"}}},
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
  };
  return kDefinitions;
}

// The dependencies of `name`, depth first in order of first use.
void CollectRos1Dependencies(std::string_view name, std::vector<std::string_view>& out) {
  for (std::string_view dep : Ros1Definitions().at(name).depends) {
    if (std::find(out.begin(), out.end(), dep) != out.end()) continue;
    out.push_back(dep);
    CollectRos1Dependencies(dep, out);
  }
}

std::string BuildRos1Definition(std::string_view name) {
  std::string text(Ros1Definitions().at(name).fields);
  std::vector<std::string_view> deps;
  CollectRos1Dependencies(name, deps);
  for (std::string_view dep : deps) {
    text += std::string(80, '=');
    text += "\nMSG: ";
    text += dep;
    text += '\n';
    text += Ros1Definitions().at(dep).fields;
  }
  return text;
}

// ---- field groups ---------------------------------------------------------------------------

struct Ros1Header {
  double stamp = 0.0;
  std::string frame_id;
};

Ros1Header ReadRos1Header(Ros1Reader& r) {
  r.Read<std::uint32_t>();  // seq
  const double stamp = Ros1StampSeconds(r.ReadTime());
  return {stamp, r.ReadString()};
}

void WriteRos1Header(Ros1Writer& w, double stamp, std::string_view frame_id) {
  w.Write<std::uint32_t>(0);  // seq
  w.WriteTime(ToRos1Time(stamp));
  w.WriteString(frame_id);
}

// geometry_msgs/Point (or Vector3) and Quaternion, projected onto the plane.
core::Pose2 ReadRos1PlanarPose(Ros1Reader& r) {
  const double x = r.Read<double>();
  const double y = r.Read<double>();
  r.Read<double>();  // z
  const double qx = r.Read<double>();
  const double qy = r.Read<double>();
  const double qz = r.Read<double>();
  const double qw = r.Read<double>();
  return core::Pose2(x, y, YawFromQuaternion(qx, qy, qz, qw));
}

void WriteRos1PlanarPose(Ros1Writer& w, const core::Pose2& pose) {
  w.WriteFloat64Values(std::array<double, 7>{
      pose.x, pose.y, 0.0, 0.0, 0.0, std::sin(0.5 * pose.theta), std::cos(0.5 * pose.theta)});
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

// The fields of a LaserScan or MultiEchoLaserScan before its ranges, into `m`; returns angle_max.
float ReadRos1ScanFields(Ros1Reader& r, ScanMessage& m) {
  Ros1Header h = ReadRos1Header(r);
  m.scan.stamp = h.stamp;
  m.frame_id = std::move(h.frame_id);
  m.scan.angle_min = r.Read<float>();
  const float angle_max = r.Read<float>();
  m.scan.angle_increment = r.Read<float>();
  r.Read<float>();  // time_increment
  r.Read<float>();  // scan_time
  m.scan.range_min = r.Read<float>();
  m.scan.range_max = r.Read<float>();
  return angle_max;
}

// sensor_msgs/LaserEcho[]: the first echo of each, +inf for a beam without one.
std::vector<float> ReadFirstEchoes(Ros1Reader& r) {
  const std::uint32_t n = r.ReadArrayLength(sizeof(std::uint32_t));
  std::vector<float> first(n, std::numeric_limits<float>::infinity());
  for (float& range : first) {
    const std::uint32_t echoes = r.ReadArrayLength(sizeof(float));
    if (echoes == 0) continue;
    range = r.Read<float>();
    r.Skip(std::size_t{echoes - 1} * sizeof(float));
  }
  return first;
}

void SkipEchoes(Ros1Reader& r) {
  const std::uint32_t n = r.ReadArrayLength(sizeof(std::uint32_t));
  for (std::uint32_t i = 0; i < n; ++i) r.SkipFloat32Array();
}

}  // namespace

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
    for (const auto& [name, md5] : Md5Sums()) texts.emplace(name, BuildRos1Definition(name));
    return texts;
  }();
  const auto it = kTexts.find(type);
  return it == kTexts.end() ? std::string_view() : std::string_view(it->second);
}

ScanMessage DecodeRos1LaserScan(std::span<const std::uint8_t> data) {
  return DecodeRos1As(kRos1LaserScanType, data, [](Ros1Reader& r) {
    ScanMessage m;
    const float angle_max = ReadRos1ScanFields(r, m);
    m.scan.ranges = r.ReadFloat32Array();
    r.SkipFloat32Array();  // intensities
    CheckScanGeometry(m, angle_max);
    return m;
  });
}

ScanMessage DecodeRos1MultiEchoLaserScan(std::span<const std::uint8_t> data) {
  return DecodeRos1As(kRos1MultiEchoLaserScanType, data, [](Ros1Reader& r) {
    ScanMessage m;
    const float angle_max = ReadRos1ScanFields(r, m);
    m.scan.ranges = ReadFirstEchoes(r);
    SkipEchoes(r);  // intensities
    CheckScanGeometry(m, angle_max);
    return m;
  });
}

OdometryMessage DecodeRos1Odometry(std::span<const std::uint8_t> data) {
  return DecodeRos1As(kRos1OdometryType, data, [](Ros1Reader& r) {
    OdometryMessage m;
    Ros1Header h = ReadRos1Header(r);
    m.stamp = h.stamp;
    m.frame_id = std::move(h.frame_id);
    m.child_frame_id = r.ReadString();
    m.pose = ReadRos1PlanarPose(r);
    r.Skip((36 + 6 + 36) * sizeof(double));  // pose covariance, twist, twist covariance
    return m;
  });
}

TfMessage DecodeRos1TfMessage(std::span<const std::uint8_t> data, std::string_view type) {
  return DecodeRos1As(type, data, [](Ros1Reader& r) {
    TfMessage m;
    const std::uint32_t n = r.ReadArrayLength(kMinRos1TransformBytes);
    m.transforms.reserve(n);
    for (std::uint32_t i = 0; i < n; ++i) {
      TransformMessage t;
      Ros1Header h = ReadRos1Header(r);
      t.stamp = h.stamp;
      t.parent = std::move(h.frame_id);
      t.child = r.ReadString();
      t.X_PC = ReadRos1PlanarPose(r);
      m.transforms.push_back(std::move(t));
    }
    return m;
  });
}

PoseStampedMessage DecodeRos1PoseStamped(std::span<const std::uint8_t> data) {
  return DecodeRos1As(kRos1PoseStampedType, data, [](Ros1Reader& r) {
    PoseStampedMessage m;
    Ros1Header h = ReadRos1Header(r);
    m.stamp = h.stamp;
    m.frame_id = std::move(h.frame_id);
    m.pose = ReadRos1PlanarPose(r);
    return m;
  });
}

PoseStampedMessage DecodeRos1PoseWithCovarianceStamped(std::span<const std::uint8_t> data) {
  return DecodeRos1As(kRos1PoseWithCovarianceStampedType, data, [](Ros1Reader& r) {
    PoseStampedMessage m;
    Ros1Header h = ReadRos1Header(r);
    m.stamp = h.stamp;
    m.frame_id = std::move(h.frame_id);
    m.pose = ReadRos1PlanarPose(r);
    r.Skip(36 * sizeof(double));  // covariance
    return m;
  });
}

std::vector<std::uint8_t> EncodeRos1LaserScan(const ScanMessage& message) {
  const core::LaserScan& s = message.scan;
  Ros1Writer w;
  WriteRos1Header(w, s.stamp, message.frame_id);
  const double angle_max = s.size() > 0 ? s.Angle(s.size() - 1) : s.angle_min;
  w.Write<float>(static_cast<float>(s.angle_min));
  w.Write<float>(static_cast<float>(angle_max));
  w.Write<float>(static_cast<float>(s.angle_increment));
  w.Write<float>(0.0f);  // time_increment
  w.Write<float>(0.0f);  // scan_time
  w.Write<float>(static_cast<float>(s.range_min));
  w.Write<float>(static_cast<float>(s.range_max));
  w.WriteFloat32Array(s.ranges);
  w.WriteFloat32Array({});  // intensities
  return w.Take();
}

std::vector<std::uint8_t> EncodeRos1Odometry(const OdometryMessage& message,
                                             const core::Twist& twist) {
  static const std::array<double, 36> kZeroCovariance{};
  Ros1Writer w;
  WriteRos1Header(w, message.stamp, message.frame_id);
  w.WriteString(message.child_frame_id);
  WriteRos1PlanarPose(w, message.pose);
  w.WriteFloat64Values(kZeroCovariance);
  w.WriteFloat64Values(std::array<double, 6>{twist.v, 0.0, 0.0, 0.0, 0.0, twist.omega});
  w.WriteFloat64Values(kZeroCovariance);
  return w.Take();
}

std::vector<std::uint8_t> EncodeRos1TfMessage(const TfMessage& message) {
  Ros1Writer w;
  w.WriteArrayLength(static_cast<std::uint32_t>(message.transforms.size()));
  for (const TransformMessage& t : message.transforms) {
    WriteRos1Header(w, t.stamp, t.parent);
    w.WriteString(t.child);
    WriteRos1PlanarPose(w, t.X_PC);
  }
  return w.Take();
}

std::vector<std::uint8_t> EncodeRos1PoseStamped(const PoseStampedMessage& message) {
  Ros1Writer w;
  WriteRos1Header(w, message.stamp, message.frame_id);
  WriteRos1PlanarPose(w, message.pose);
  return w.Take();
}

}  // namespace retrace::logs
