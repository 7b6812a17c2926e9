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
#include "logs/internal/ros_fields.hpp"

namespace retrace::logs {
namespace {

// The smallest serialized geometry_msgs/TransformStamped: stamp (8), two string lengths (8),
// translation and rotation (56). A TFMessage's count is checked against it before allocating.
constexpr std::size_t kMinTransformStampedBytes = 72;

// ---- ros2msg definitions -------------------------------------------------------------------

const internal::MessageDefinitions& Definitions() {
  static const internal::MessageDefinitions kDefinitions = internal::WithSharedGeometry({
      {"builtin_interfaces/Time", {"int32 sec\nuint32 nanosec\n", {}}},
      {"std_msgs/Header",
       {"builtin_interfaces/Time stamp\nstring frame_id\n", {"builtin_interfaces/Time"}}},
      {"geometry_msgs/Quaternion", {"float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n", {}}},
      {"geometry_msgs/TransformStamped",
       {"std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n",
        {"std_msgs/Header", "geometry_msgs/Transform"}}},
      {"sensor_msgs/LaserScan",
       {"std_msgs/Header header\n"
        "float32 angle_min\n"
        "float32 angle_max\n"
        "float32 angle_increment\n"
        "float32 time_increment\n"
        "float32 scan_time\n"
        "float32 range_min\n"
        "float32 range_max\n"
        "float32[] ranges\n"
        "float32[] intensities\n",
        {"std_msgs/Header"}}},
      {"nav_msgs/Odometry",
       {"std_msgs/Header header\n"
        "string child_frame_id\n"
        "geometry_msgs/PoseWithCovariance pose\n"
        "geometry_msgs/TwistWithCovariance twist\n",
        {"std_msgs/Header", "geometry_msgs/PoseWithCovariance",
         "geometry_msgs/TwistWithCovariance"}}},
      {"tf2_msgs/TFMessage",
       {"geometry_msgs/TransformStamped[] transforms\n", {"geometry_msgs/TransformStamped"}}},
      {"geometry_msgs/PoseStamped",
       {"std_msgs/Header header\ngeometry_msgs/Pose pose\n",
        {"std_msgs/Header", "geometry_msgs/Pose"}}},
  });
  return kDefinitions;
}

// "sensor_msgs/msg/LaserScan" -> "sensor_msgs/LaserScan".
std::string ShortName(std::string_view type) {
  const std::size_t slash = type.find("/msg/");
  if (slash == std::string_view::npos) return std::string(type);
  return std::string(type.substr(0, slash)) + "/" + std::string(type.substr(slash + 5));
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

namespace internal {

StampedFrame ReadHeader(CdrReader& r) {
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

}  // namespace internal

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
  return DecodeAs(kLaserScanType, cdr, [](CdrReader& r) { return internal::ReadLaserScan(r); });
}

std::vector<std::uint8_t> EncodeLaserScan(const ScanMessage& message) {
  CdrWriter w;
  internal::WriteLaserScan(w, message);
  return w.Take();
}

OdometryMessage DecodeOdometry(std::span<const std::uint8_t> cdr) {
  return DecodeAs(kOdometryType, cdr, [](CdrReader& r) { return internal::ReadOdometry(r); });
}

std::vector<std::uint8_t> EncodeOdometry(const OdometryMessage& message, const core::Twist& twist) {
  CdrWriter w;
  internal::WriteOdometry(w, message, twist);
  return w.Take();
}

TfMessage DecodeTfMessage(std::span<const std::uint8_t> cdr) {
  return DecodeAs(kTfMessageType, cdr, [](CdrReader& r) {
    return internal::ReadTfMessage(r, kMinTransformStampedBytes);
  });
}

std::vector<std::uint8_t> EncodeTfMessage(const TfMessage& message) {
  CdrWriter w;
  internal::WriteTfMessage(w, message);
  return w.Take();
}

PoseStampedMessage DecodePoseStamped(std::span<const std::uint8_t> cdr) {
  return DecodeAs(kPoseStampedType, cdr, [](CdrReader& r) { return internal::ReadPoseStamped(r); });
}

std::vector<std::uint8_t> EncodePoseStamped(const PoseStampedMessage& message) {
  CdrWriter w;
  internal::WritePoseStamped(w, message);
  return w.Take();
}

std::string_view RosMessageDefinition(std::string_view type) {
  static const std::map<std::string_view, std::string> kTexts = [] {
    std::map<std::string_view, std::string> texts;
    for (std::string_view type_name :
         {kLaserScanType, kOdometryType, kTfMessageType, kPoseStampedType}) {
      texts.emplace(type_name, internal::FullDefinition(Definitions(), ShortName(type_name)));
    }
    return texts;
  }();
  const auto it = kTexts.find(type);
  return it == kTexts.end() ? std::string_view() : std::string_view(it->second);
}

}  // namespace retrace::logs
