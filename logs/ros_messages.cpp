#include "logs/ros_messages.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "core/config.hpp"
#include "core/errors.hpp"
#include "core/limits.hpp"
#include "core/quaternion.hpp"
#include "logs/cdr.hpp"

namespace retrace::logs {
namespace {

// The smallest serialized geometry_msgs/TransformStamped: stamp (8), two string lengths (8),
// translation and rotation (56). A TFMessage's count is checked against it before allocating.
constexpr std::size_t kMinTransformStampedBytes = 72;

// ---- ros2msg definitions -------------------------------------------------------------------

struct Definition {
  std::string_view name;                  // "pkg/Type" as in a "MSG:" line
  std::string_view fields;                // one "type name" line per field
  std::vector<std::string_view> depends;  // the "pkg/Type" names its fields use
};

const std::map<std::string_view, Definition>& Definitions() {
  static const std::map<std::string_view, Definition> kDefinitions = [] {
    std::map<std::string_view, Definition> d;
    const auto add = [&d](Definition def) { d.emplace(def.name, std::move(def)); };
    add({"builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n", {}});
    add({"std_msgs/Header",
         "builtin_interfaces/Time stamp\nstring frame_id\n",
         {"builtin_interfaces/Time"}});
    add({"geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n", {}});
    add({"geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n", {}});
    add({"geometry_msgs/Quaternion", "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n", {}});
    add({"geometry_msgs/Pose",
         "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n",
         {"geometry_msgs/Point", "geometry_msgs/Quaternion"}});
    add({"geometry_msgs/PoseWithCovariance",
         "geometry_msgs/Pose pose\nfloat64[36] covariance\n",
         {"geometry_msgs/Pose"}});
    add({"geometry_msgs/Twist",
         "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n",
         {"geometry_msgs/Vector3"}});
    add({"geometry_msgs/TwistWithCovariance",
         "geometry_msgs/Twist twist\nfloat64[36] covariance\n",
         {"geometry_msgs/Twist"}});
    add({"geometry_msgs/Transform",
         "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n",
         {"geometry_msgs/Vector3", "geometry_msgs/Quaternion"}});
    add({"geometry_msgs/TransformStamped",
         "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n",
         {"std_msgs/Header", "geometry_msgs/Transform"}});
    add({"sensor_msgs/LaserScan",
         "std_msgs/Header header\n"
         "float32 angle_min\n"
         "float32 angle_max\n"
         "float32 angle_increment\n"
         "float32 time_increment\n"
         "float32 scan_time\n"
         "float32 range_min\n"
         "float32 range_max\n"
         "float32[] ranges\n"
         "float32[] intensities\n",
         {"std_msgs/Header"}});
    add({"nav_msgs/Odometry",
         "std_msgs/Header header\n"
         "string child_frame_id\n"
         "geometry_msgs/PoseWithCovariance pose\n"
         "geometry_msgs/TwistWithCovariance twist\n",
         {"std_msgs/Header", "geometry_msgs/PoseWithCovariance",
          "geometry_msgs/TwistWithCovariance"}});
    add({"tf2_msgs/TFMessage",
         "geometry_msgs/TransformStamped[] transforms\n",
         {"geometry_msgs/TransformStamped"}});
    add({"geometry_msgs/PoseStamped",
         "std_msgs/Header header\ngeometry_msgs/Pose pose\n",
         {"std_msgs/Header", "geometry_msgs/Pose"}});
    return d;
  }();
  return kDefinitions;
}

// The dependencies of `name`, depth first in order of first use.
void CollectDependencies(std::string_view name, std::vector<std::string_view>& out) {
  for (std::string_view dep : Definitions().at(name).depends) {
    if (std::find(out.begin(), out.end(), dep) != out.end()) continue;
    out.push_back(dep);
    CollectDependencies(dep, out);
  }
}

std::string BuildDefinition(std::string_view name) {
  std::string text(Definitions().at(name).fields);
  std::vector<std::string_view> deps;
  CollectDependencies(name, deps);
  for (std::string_view dep : deps) {
    text += std::string(80, '=');
    text += "\nMSG: ";
    text += dep;
    text += '\n';
    text += Definitions().at(dep).fields;
  }
  return text;
}

// "sensor_msgs/msg/LaserScan" -> "sensor_msgs/LaserScan".
std::string ShortName(std::string_view type) {
  const std::size_t slash = type.find("/msg/");
  if (slash == std::string_view::npos) return std::string(type);
  return std::string(type.substr(0, slash)) + "/" + std::string(type.substr(slash + 5));
}

// ---- field groups ---------------------------------------------------------------------------

struct Header {
  double stamp = 0.0;
  std::string frame_id;
};

Header ReadHeader(CdrReader& r) {
  RosTime t;
  t.sec = r.Read<std::int32_t>();
  t.nanosec = r.Read<std::uint32_t>();
  return {StampSeconds(t), r.ReadString()};
}

void WriteHeader(CdrWriter& w, double stamp, std::string_view frame_id) {
  const RosTime t = ToRosTime(stamp);
  w.Write<std::int32_t>(t.sec);
  w.Write<std::uint32_t>(t.nanosec);
  w.WriteString(frame_id);
}

// geometry_msgs/Point (or Vector3) and Quaternion, projected onto the plane.
core::Pose2 ReadPlanarPose(CdrReader& r) {
  const double x = r.Read<double>();
  const double y = r.Read<double>();
  r.Read<double>();  // z
  const double qx = r.Read<double>();
  const double qy = r.Read<double>();
  const double qz = r.Read<double>();
  const double qw = r.Read<double>();
  return core::Pose2(x, y, YawFromQuaternion(qx, qy, qz, qw));
}

void WritePlanarPose(CdrWriter& w, const core::Pose2& pose) {
  w.Write<double>(pose.x);
  w.Write<double>(pose.y);
  w.Write<double>(0.0);
  w.Write<double>(0.0);
  w.Write<double>(0.0);
  w.Write<double>(std::sin(0.5 * pose.theta));
  w.Write<double>(std::cos(0.5 * pose.theta));
}

// Runs `decode` on a reader over `cdr`, prefixing any IoError with the type name.
template <typename Decode>
auto DecodeAs(std::string_view type, std::span<const std::uint8_t> cdr, Decode decode) {
  try {
    CdrReader r(cdr);
    return decode(r);
  } catch (const core::IoError& e) {
    throw core::IoError(std::string(type) + ": " + e.what());
  }
}

std::string Num(double v) { return core::FormatNumber(v); }

// A float32 field in its shortest round-trip form ("0.44", not "0.4399999976158142").
std::string NumF(float v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  return ec == std::errc() ? std::string(buf, end) : std::string("?");
}

}  // namespace

double StampSeconds(RosTime t) {
  return static_cast<double>(t.sec) + static_cast<double>(t.nanosec) * 1e-9;
}

RosTime ToRosTime(double stamp) {
  if (!std::isfinite(stamp)) throw core::IoError("stamp " + Num(stamp) + " is not finite");
  const double sec = std::floor(stamp);
  if (sec < static_cast<double>(std::numeric_limits<std::int32_t>::min()) ||
      sec > static_cast<double>(std::numeric_limits<std::int32_t>::max())) {
    throw core::IoError("stamp " + Num(stamp) +
                        " s is outside the int32 seconds of builtin_interfaces/Time");
  }
  RosTime t;
  std::int64_t s = static_cast<std::int64_t>(sec);
  std::int64_t ns = std::llround((stamp - sec) * 1e9);
  if (ns >= 1'000'000'000) {
    ns -= 1'000'000'000;
    ++s;
  }
  if (s > std::numeric_limits<std::int32_t>::max()) {
    throw core::IoError("stamp " + Num(stamp) +
                        " s is outside the int32 seconds of builtin_interfaces/Time");
  }
  t.sec = static_cast<std::int32_t>(s);
  t.nanosec = static_cast<std::uint32_t>(ns);
  return t;
}

double YawFromQuaternion(double x, double y, double z, double w) {
  const std::optional<double> yaw = core::QuaternionYaw(x, y, z, w);
  if (!yaw) {
    const bool finite =
        std::isfinite(x) && std::isfinite(y) && std::isfinite(z) && std::isfinite(w);
    throw core::IoError("quaternion (" + Num(x) + ", " + Num(y) + ", " + Num(z) + ", " + Num(w) +
                        ")" + (finite ? " has (near) zero norm" : " has a non-finite component"));
  }
  return *yaw;
}

void CheckScanGeometry(ScanMessage& m, float angle_max) {
  const std::size_t n = m.scan.ranges.size();
  if (n > static_cast<std::size_t>(core::kMaxBeams)) {
    throw core::IoError("the scan has " + std::to_string(n) + " ranges; retrace's limit is " +
                        std::to_string(core::kMaxBeams));
  }
  if (n == 0) return;
  const double expected = m.scan.Angle(n - 1);
  // A little for the float32 rounding of the three angles.
  const double rounding = 1e-6 * (1.0 + std::abs(expected));
  const double increment = std::abs(m.scan.angle_increment);
  const double off = std::abs(static_cast<double>(angle_max) - expected);
  if (!(off <= kAngleMaxSlackIncrements * increment + rounding)) {
    throw core::IoError("angle_max " + NumF(angle_max) +
                        " does not match angle_min + (n - 1) * angle_increment = " +
                        NumF(static_cast<float>(expected)) + " for n = " + std::to_string(n) +
                        " ranges (more than " + Num(kAngleMaxSlackIncrements) +
                        " increments apart)");
  }
  // Drivers that count n increments instead of n - 1 (or round the field of view): the beams are
  // at angle_min + i * angle_increment all the same, as every ROS consumer reads them; the caller
  // notes it.
  if (off > 0.5 * increment + rounding) m.angle_max = angle_max;
}

ScanMessage DecodeLaserScan(std::span<const std::uint8_t> cdr) {
  return DecodeAs(kLaserScanType, cdr, [](CdrReader& r) {
    ScanMessage m;
    Header h = ReadHeader(r);
    m.scan.stamp = h.stamp;
    m.frame_id = std::move(h.frame_id);
    const float angle_min = r.Read<float>();
    const float angle_max = r.Read<float>();
    const float angle_increment = r.Read<float>();
    r.Read<float>();  // time_increment
    r.Read<float>();  // scan_time
    m.scan.range_min = r.Read<float>();
    m.scan.range_max = r.Read<float>();
    m.scan.ranges = r.ReadFloat32Sequence();
    r.ReadFloat32Sequence();  // intensities
    m.scan.angle_min = angle_min;
    m.scan.angle_increment = angle_increment;
    CheckScanGeometry(m, angle_max);
    return m;
  });
}

std::vector<std::uint8_t> EncodeLaserScan(const ScanMessage& message) {
  const core::LaserScan& s = message.scan;
  CdrWriter w;
  WriteHeader(w, s.stamp, message.frame_id);
  const double angle_max = s.size() > 0 ? s.Angle(s.size() - 1) : s.angle_min;
  w.Write<float>(static_cast<float>(s.angle_min));
  w.Write<float>(static_cast<float>(angle_max));
  w.Write<float>(static_cast<float>(s.angle_increment));
  w.Write<float>(0.0f);  // time_increment
  w.Write<float>(0.0f);  // scan_time
  w.Write<float>(static_cast<float>(s.range_min));
  w.Write<float>(static_cast<float>(s.range_max));
  w.WriteFloat32Sequence(s.ranges);
  w.WriteFloat32Sequence({});  // intensities
  return w.Take();
}

OdometryMessage DecodeOdometry(std::span<const std::uint8_t> cdr) {
  return DecodeAs(kOdometryType, cdr, [](CdrReader& r) {
    OdometryMessage m;
    Header h = ReadHeader(r);
    m.stamp = h.stamp;
    m.frame_id = std::move(h.frame_id);
    m.child_frame_id = r.ReadString();
    m.pose = ReadPlanarPose(r);
    r.SkipFloat64Array(36);     // pose covariance
    r.SkipFloat64Array(3 + 3);  // twist: linear, angular
    r.SkipFloat64Array(36);     // twist covariance
    return m;
  });
}

std::vector<std::uint8_t> EncodeOdometry(const OdometryMessage& message, const core::Twist& twist) {
  static const std::array<double, 36> kZeroCovariance{};
  CdrWriter w;
  WriteHeader(w, message.stamp, message.frame_id);
  w.WriteString(message.child_frame_id);
  WritePlanarPose(w, message.pose);
  w.WriteFloat64Array(kZeroCovariance);
  w.WriteFloat64Array(std::array<double, 6>{twist.v, 0.0, 0.0, 0.0, 0.0, twist.omega});
  w.WriteFloat64Array(kZeroCovariance);
  return w.Take();
}

TfMessage DecodeTfMessage(std::span<const std::uint8_t> cdr) {
  return DecodeAs(kTfMessageType, cdr, [](CdrReader& r) {
    TfMessage m;
    const std::uint32_t n = r.ReadSequenceLength(kMinTransformStampedBytes);
    m.transforms.reserve(n);
    for (std::uint32_t i = 0; i < n; ++i) {
      TransformMessage t;
      Header h = ReadHeader(r);
      t.stamp = h.stamp;
      t.parent = std::move(h.frame_id);
      t.child = r.ReadString();
      t.X_PC = ReadPlanarPose(r);
      m.transforms.push_back(std::move(t));
    }
    return m;
  });
}

std::vector<std::uint8_t> EncodeTfMessage(const TfMessage& message) {
  CdrWriter w;
  w.WriteSequenceLength(static_cast<std::uint32_t>(message.transforms.size()));
  for (const TransformMessage& t : message.transforms) {
    WriteHeader(w, t.stamp, t.parent);
    w.WriteString(t.child);
    WritePlanarPose(w, t.X_PC);
  }
  return w.Take();
}

PoseStampedMessage DecodePoseStamped(std::span<const std::uint8_t> cdr) {
  return DecodeAs(kPoseStampedType, cdr, [](CdrReader& r) {
    PoseStampedMessage m;
    Header h = ReadHeader(r);
    m.stamp = h.stamp;
    m.frame_id = std::move(h.frame_id);
    m.pose = ReadPlanarPose(r);
    return m;
  });
}

std::vector<std::uint8_t> EncodePoseStamped(const PoseStampedMessage& message) {
  CdrWriter w;
  WriteHeader(w, message.stamp, message.frame_id);
  WritePlanarPose(w, message.pose);
  return w.Take();
}

std::string_view RosMessageDefinition(std::string_view type) {
  static const std::map<std::string_view, std::string> kTexts = [] {
    std::map<std::string_view, std::string> texts;
    for (std::string_view type_name :
         {kLaserScanType, kOdometryType, kTfMessageType, kPoseStampedType}) {
      texts.emplace(type_name, BuildDefinition(ShortName(type_name)));
    }
    return texts;
  }();
  const auto it = kTexts.find(type);
  return it == kTexts.end() ? std::string_view() : std::string_view(it->second);
}

}  // namespace retrace::logs
