#include "logs/ros_messages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "logs/cdr.hpp"
#include "tests/support/io_error_of.hpp"

namespace retrace::logs {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace ros_messages_test {

using Buffer = std::vector<std::uint8_t>;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

using testing::IoErrorOf;

bool Contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

ScanMessage SampleScan() {
  ScanMessage m;
  m.frame_id = "laser";
  m.scan.stamp = 1585866235.25;
  m.scan.angle_min = -1.5;
  m.scan.angle_increment = 0.25;
  m.scan.range_min = 0.125;
  m.scan.range_max = 30.0;
  m.scan.ranges = {1.0f,  kInf,  -kInf, kNaN,  2.5f,  0.0f, 29.75f,
                   12.0f, 13.0f, 14.0f, 15.0f, 16.0f, 17.0f};
  return m;
}

// Each encoding, decoded from every proper prefix, is refused with the type's name.
template <typename Decode>
void ExpectEveryPrefixRefused(const Buffer& full, Decode decode, const std::string& type) {
  for (std::size_t n = 0; n < full.size(); ++n) {
    const Buffer prefix(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(n));
    const std::string error = IoErrorOf([&] { decode(prefix); });
    EXPECT_TRUE(Contains(error, type + ": ")) << "prefix " << n << ": '" << error << "'";
  }
}

TEST(LaserScanCodec, RoundTripsWithNanAndInfiniteRanges) {
  const ScanMessage in = SampleScan();
  const ScanMessage out = DecodeLaserScan(EncodeLaserScan(in));
  EXPECT_EQ(out.frame_id, "laser");
  EXPECT_DOUBLE_EQ(out.scan.stamp, in.scan.stamp);
  EXPECT_EQ(out.scan.angle_min, -1.5);
  EXPECT_EQ(out.scan.angle_increment, 0.25);
  EXPECT_EQ(out.scan.range_min, 0.125);
  EXPECT_EQ(out.scan.range_max, 30.0);
  ASSERT_EQ(out.scan.ranges.size(), in.scan.ranges.size());
  for (std::size_t i = 0; i < in.scan.ranges.size(); ++i) {
    if (std::isnan(in.scan.ranges[i])) {
      EXPECT_TRUE(std::isnan(out.scan.ranges[i]));
    } else {
      EXPECT_EQ(out.scan.ranges[i], in.scan.ranges[i]) << i;
    }
  }
  EXPECT_TRUE(out.scan.NoReturn(1));
  EXPECT_FALSE(out.scan.Valid(2));
  EXPECT_FALSE(out.scan.Valid(3));
}

TEST(LaserScanCodec, WritesAngleMaxAsTheLastBeamsAngle) {
  const Buffer b = EncodeLaserScan(SampleScan());
  CdrReader r(b);
  r.Read<std::int32_t>();
  r.Read<std::uint32_t>();
  EXPECT_EQ(r.ReadString(), "laser");
  EXPECT_EQ(r.Read<float>(), -1.5f);
  EXPECT_EQ(r.Read<float>(), -1.5f + 12 * 0.25f);  // angle_max
  EXPECT_EQ(r.Read<float>(), 0.25f);
  EXPECT_EQ(r.Read<float>(), 0.0f);  // time_increment
  EXPECT_EQ(r.Read<float>(), 0.0f);  // scan_time
  EXPECT_EQ(r.Read<float>(), 0.125f);
  EXPECT_EQ(r.Read<float>(), 30.0f);
  EXPECT_EQ(r.ReadFloat32Sequence().size(), 13u);
  EXPECT_TRUE(r.ReadFloat32Sequence().empty());  // intensities
  EXPECT_EQ(r.remaining(), 0u);
}

// A LaserScan built field by field with the given angles and ranges.
Buffer HandBuiltScan(float angle_min, float angle_max, float increment, std::vector<float> ranges) {
  CdrWriter w;
  w.Write<std::int32_t>(100);
  w.Write<std::uint32_t>(500'000'000);
  w.WriteString("base_scan");
  w.Write<float>(angle_min);
  w.Write<float>(angle_max);
  w.Write<float>(increment);
  w.Write<float>(0.001f);
  w.Write<float>(0.1f);
  w.Write<float>(0.02f);
  w.Write<float>(5.6f);
  w.WriteFloat32Sequence(ranges);
  w.WriteFloat32Sequence(std::vector<float>(ranges.size(), 100.0f));  // intensities
  return w.Take();
}

TEST(LaserScanCodec, ChecksAngleMaxToHalfAnIncrement) {
  const std::vector<float> ranges(5, 1.0f);
  // angle_min + 4 * 0.1 = 0.4; within half an increment is accepted.
  const ScanMessage ok = DecodeLaserScan(HandBuiltScan(0.0f, 0.44f, 0.1f, ranges));
  EXPECT_EQ(ok.frame_id, "base_scan");
  EXPECT_DOUBLE_EQ(ok.scan.stamp, 100.5);
  EXPECT_EQ(ok.scan.size(), 5u);
  EXPECT_NEAR(ok.scan.range_max, 5.6, 1e-6);
  EXPECT_FALSE(ok.angle_max.has_value());
  // Clockwise scanners have a negative increment.
  EXPECT_NO_THROW(DecodeLaserScan(HandBuiltScan(1.0f, 0.6f, -0.1f, ranges)));
  EXPECT_NE(IoErrorOf([&] { DecodeLaserScan(HandBuiltScan(0.0f, 0.4f, kNaN, ranges)); }), "");
  // An empty scan has nothing to check.
  EXPECT_NO_THROW(DecodeLaserScan(HandBuiltScan(0.0f, 3.0f, 0.1f, {})));
}

// Real drivers write angle_max = angle_min + n * increment (one increment too far) or round the
// field of view (two): every ROS consumer places beam i at angle_min + i * increment, and so
// does retrace, saying so; a scan further off than two increments is refused.
TEST(LaserScanCodec, AngleMaxOneOrTwoIncrementsOffIsUsedByAngleMinAndIncrement) {
  const std::vector<float> ranges(5, 1.0f);
  for (const float angle_max : {0.5f, 0.6f, 0.3f, 0.2f}) {
    const ScanMessage m = DecodeLaserScan(HandBuiltScan(0.0f, angle_max, 0.1f, ranges));
    ASSERT_TRUE(m.angle_max.has_value()) << angle_max;
    EXPECT_NEAR(*m.angle_max, angle_max, 1e-7);
    EXPECT_EQ(m.scan.angle_min, 0.0);
    EXPECT_NEAR(m.scan.Angle(4), 0.4, 1e-6);  // the last beam, by angle_min + i * increment
  }
  const std::string error =
      IoErrorOf([&] { DecodeLaserScan(HandBuiltScan(0.0f, 0.7f, 0.1f, ranges)); });
  EXPECT_TRUE(Contains(error,
                       "sensor_msgs/msg/LaserScan: angle_max 0.7 does not match "
                       "angle_min + (n - 1) * angle_increment = 0.4"))
      << error;
  EXPECT_TRUE(Contains(error, "for n = 5 ranges (more than 2 increments apart)")) << error;
}

TEST(LaserScanCodec, DecodesBigEndian) {
  // The header and fields of a LaserScan in big endian, as a big-endian host would send it.
  const Buffer b = {
      0x00, 0x00, 0x00, 0x00,                        // CDR big endian
      0x00, 0x00, 0x00, 0x0A,                        // sec 10
      0x1D, 0xCD, 0x65, 0x00,                        // nanosec 500000000
      0x00, 0x00, 0x00, 0x03, 'l', 'x', 0x00, 0x00,  // "lx", pad
      0xBF, 0x80, 0x00, 0x00,                        // angle_min -1
      0x3F, 0x80, 0x00, 0x00,                        // angle_max 1
      0x3F, 0x80, 0x00, 0x00,                        // angle_increment 1
      0x00, 0x00, 0x00, 0x00,                        // time_increment
      0x00, 0x00, 0x00, 0x00,                        // scan_time
      0x3F, 0x00, 0x00, 0x00,                        // range_min 0.5
      0x41, 0x20, 0x00, 0x00,                        // range_max 10
      0x00, 0x00, 0x00, 0x03,                        // 3 ranges
      0x40, 0x00, 0x00, 0x00,                        // 2
      0x7F, 0x80, 0x00, 0x00,                        // +inf
      0x7F, 0xC0, 0x00, 0x00,                        // NaN
      0x00, 0x00, 0x00, 0x00,                        // no intensities
  };
  const ScanMessage m = DecodeLaserScan(b);
  EXPECT_EQ(m.frame_id, "lx");
  EXPECT_DOUBLE_EQ(m.scan.stamp, 10.5);
  EXPECT_EQ(m.scan.angle_min, -1.0);
  EXPECT_EQ(m.scan.angle_increment, 1.0);
  EXPECT_EQ(m.scan.range_min, 0.5);
  EXPECT_EQ(m.scan.range_max, 10.0);
  ASSERT_EQ(m.scan.size(), 3u);
  EXPECT_EQ(m.scan.ranges[0], 2.0f);
  EXPECT_EQ(m.scan.ranges[1], kInf);
  EXPECT_TRUE(std::isnan(m.scan.ranges[2]));
}

TEST(LaserScanCodec, RefusesMalformedMessages) {
  ExpectEveryPrefixRefused(EncodeLaserScan(SampleScan()), DecodeLaserScan,
                           "sensor_msgs/msg/LaserScan");
  // A range count of 2^32 - 1 is refused before anything is allocated.
  CdrWriter w;
  w.Write<std::int32_t>(0);
  w.Write<std::uint32_t>(0);
  w.WriteString("");
  for (int i = 0; i < 7; ++i) w.Write<float>(0.0f);
  w.Write<std::uint32_t>(0xFFFFFFFFu);
  EXPECT_TRUE(Contains(IoErrorOf([&] { DecodeLaserScan(w.data()); }),
                       "sensor_msgs/msg/LaserScan: sequence of 4294967295 elements"));
  EXPECT_TRUE(Contains(IoErrorOf([] {
                         DecodeLaserScan(Buffer{0x00, 0x03, 0x00, 0x00});
                       }),
                       "sensor_msgs/msg/LaserScan: unsupported CDR encapsulation"));
}

TEST(OdometryCodec, RoundTripsThePlanarPoseAndWritesTheTwist) {
  OdometryMessage in;
  in.stamp = -3.75;
  in.frame_id = "odom";
  in.child_frame_id = "base_link";
  in.pose = core::Pose2(1.5, -2.25, 2.0);
  const Buffer b = EncodeOdometry(in, core::Twist{0.5, -0.25});
  const OdometryMessage out = DecodeOdometry(b);
  EXPECT_DOUBLE_EQ(out.stamp, -3.75);
  EXPECT_EQ(out.frame_id, "odom");
  EXPECT_EQ(out.child_frame_id, "base_link");
  EXPECT_EQ(out.pose.x, 1.5);
  EXPECT_EQ(out.pose.y, -2.25);
  EXPECT_NEAR(out.pose.theta, 2.0, 1e-12);

  // The layout field by field: header, child frame, pose, covariance, twist, covariance.
  CdrReader r(b);
  EXPECT_EQ(r.Read<std::int32_t>(), -4);
  EXPECT_EQ(r.Read<std::uint32_t>(), 250'000'000u);
  EXPECT_EQ(r.ReadString(), "odom");
  EXPECT_EQ(r.ReadString(), "base_link");
  EXPECT_EQ(r.Read<double>(), 1.5);
  EXPECT_EQ(r.Read<double>(), -2.25);
  EXPECT_EQ(r.Read<double>(), 0.0);
  EXPECT_EQ(r.Read<double>(), 0.0);
  EXPECT_EQ(r.Read<double>(), 0.0);
  EXPECT_NEAR(r.Read<double>(), std::sin(1.0), 1e-15);
  EXPECT_NEAR(r.Read<double>(), std::cos(1.0), 1e-15);
  r.SkipFloat64Array(36);
  EXPECT_EQ(r.Read<double>(), 0.5);
  EXPECT_EQ(r.Read<double>(), 0.0);
  EXPECT_EQ(r.Read<double>(), 0.0);
  EXPECT_EQ(r.Read<double>(), 0.0);
  EXPECT_EQ(r.Read<double>(), 0.0);
  EXPECT_EQ(r.Read<double>(), -0.25);
  r.SkipFloat64Array(36);
  EXPECT_EQ(r.remaining(), 0u);

  ExpectEveryPrefixRefused(b, DecodeOdometry, "nav_msgs/msg/Odometry");
}

TEST(TfMessageCodec, RoundTripsSeveralTransforms) {
  TfMessage in;
  in.transforms.push_back({12.000000001, "map", "odom", core::Pose2(1, 2, -3.0)});
  in.transforms.push_back({12.5, "odom", "base_link", core::Pose2(-4, 5.5, 0.0)});
  const Buffer b = EncodeTfMessage(in);
  const TfMessage out = DecodeTfMessage(b);
  ASSERT_EQ(out.transforms.size(), 2u);
  EXPECT_NEAR(out.transforms[0].stamp, 12.000000001, 1e-9);
  EXPECT_EQ(out.transforms[0].parent, "map");
  EXPECT_EQ(out.transforms[0].child, "odom");
  EXPECT_EQ(out.transforms[0].X_PC.x, 1.0);
  EXPECT_EQ(out.transforms[0].X_PC.y, 2.0);
  EXPECT_NEAR(out.transforms[0].X_PC.theta, -3.0, 1e-12);
  EXPECT_EQ(out.transforms[1].parent, "odom");
  EXPECT_EQ(out.transforms[1].child, "base_link");
  EXPECT_EQ(out.transforms[1].X_PC.x, -4.0);
  EXPECT_EQ(out.transforms[1].X_PC.theta, 0.0);

  EXPECT_TRUE(DecodeTfMessage(EncodeTfMessage({})).transforms.empty());
  ExpectEveryPrefixRefused(b, DecodeTfMessage, "tf2_msgs/msg/TFMessage");
}

TEST(TfMessageCodec, RefusesAHugeTransformCount) {
  const Buffer b = {0x00, 0x01, 0x00, 0x00, 0xFF, 0xFF, 0xFF, 0xFF, 0, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(IoErrorOf([&] { DecodeTfMessage(b); }),
            "tf2_msgs/msg/TFMessage: sequence of 4294967295 elements at byte 0 needs at least "
            "309237645240 bytes, 8 left");
}

TEST(PoseStampedCodec, RoundTrips) {
  PoseStampedMessage in;
  in.stamp = 1700000000.125;
  in.frame_id = "map";
  in.pose = core::Pose2(10.0, 20.0, -1.0);
  const Buffer b = EncodePoseStamped(in);
  const PoseStampedMessage out = DecodePoseStamped(b);
  EXPECT_DOUBLE_EQ(out.stamp, in.stamp);
  EXPECT_EQ(out.frame_id, "map");
  EXPECT_EQ(out.pose.x, 10.0);
  EXPECT_EQ(out.pose.y, 20.0);
  EXPECT_NEAR(out.pose.theta, -1.0, 1e-12);
  ExpectEveryPrefixRefused(b, DecodePoseStamped, "geometry_msgs/msg/PoseStamped");
}

// A PoseStamped with the given quaternion.
Buffer PoseWithQuaternion(double x, double y, double z, double w) {
  CdrWriter b;
  b.Write<std::int32_t>(1);
  b.Write<std::uint32_t>(0);
  b.WriteString("map");
  b.WriteFloat64Array(std::vector<double>{0.0, 0.0, 0.0, x, y, z, w});
  return b.Take();
}

TEST(PoseStampedCodec, RefusesZeroAndNonFiniteQuaternions) {
  EXPECT_EQ(IoErrorOf([] { DecodePoseStamped(PoseWithQuaternion(0, 0, 0, 0)); }),
            "geometry_msgs/msg/PoseStamped: quaternion (0, 0, 0, 0) has (near) zero norm");
  EXPECT_EQ(IoErrorOf([] { DecodePoseStamped(PoseWithQuaternion(0, 0, 1e-12, 0)); }),
            "geometry_msgs/msg/PoseStamped: quaternion (0, 0, 1e-12, 0) has (near) zero norm");
  EXPECT_TRUE(Contains(IoErrorOf([] {
                         DecodePoseStamped(
                             PoseWithQuaternion(0, 0, std::numeric_limits<double>::infinity(), 1));
                       }),
                       "has a non-finite component"));
  EXPECT_TRUE(Contains(IoErrorOf([] { DecodePoseStamped(PoseWithQuaternion(0, kNaN, 0, 1)); }),
                       "has a non-finite component"));
  // Huge components are scaled first, not squared into infinity.
  const PoseStampedMessage huge = DecodePoseStamped(PoseWithQuaternion(0, 0, 1e200, 1e200));
  EXPECT_NEAR(huge.pose.theta, core::kPi / 2, 1e-12);
}

TEST(YawFromQuaternion, MatchesTheZyxYawForUnitAndScaledQuaternions) {
  EXPECT_EQ(YawFromQuaternion(0, 0, 0, 1), 0.0);
  EXPECT_NEAR(YawFromQuaternion(0, 0, std::sin(0.4), std::cos(0.4)), 0.8, 1e-15);
  EXPECT_NEAR(YawFromQuaternion(0, 0, 3 * std::sin(0.4), 3 * std::cos(0.4)), 0.8, 1e-15);
}

TEST(YawFromQuaternion, RefusesTinyNormsAndKeepsHugeOnes) {
  EXPECT_NE(IoErrorOf([] { YawFromQuaternion(0, 0, 1e-300, 1e-300); }), "");
  EXPECT_NEAR(YawFromQuaternion(1e200, 0, 0, 0), core::WrapAngle(0.0), 1e-12);  // roll of pi
  EXPECT_NEAR(YawFromQuaternion(0, 0, 1e308, -1e308), -core::kPi / 2, 1e-12);
  EXPECT_NEAR(std::abs(YawFromQuaternion(0, 0, 1e200, 0)), core::kPi, 1e-12);
  EXPECT_NEAR(YawFromQuaternion(-1e-5, 2e-5, 0.5e-5, 1e-5),
              std::atan2(2 * (1 * 0.5 + -1 * 2), 1 + 1 - 4 - 0.25), 1e-12);
}

TEST(RosTime, ConvertsStampsBothWays) {
  EXPECT_EQ(StampSeconds({10, 500'000'000}), 10.5);
  EXPECT_EQ(StampSeconds({-1, 0}), -1.0);
  const RosTime t = ToRosTime(-0.25);
  EXPECT_EQ(t.sec, -1);
  EXPECT_EQ(t.nanosec, 750'000'000u);
  const RosTime carry = ToRosTime(2.9999999999);
  EXPECT_EQ(carry.sec, 3);
  EXPECT_EQ(carry.nanosec, 0u);
  EXPECT_EQ(ToRosTime(1585866235.5).nanosec, 500'000'000u);
  EXPECT_TRUE(Contains(IoErrorOf([] { ToRosTime(3e9); }), "outside the int32 seconds"));
  EXPECT_TRUE(Contains(IoErrorOf([] { ToRosTime(kNaN); }), "not finite"));
  ScanMessage late = SampleScan();
  late.scan.stamp = 1e10;
  EXPECT_TRUE(Contains(IoErrorOf([&] { EncodeLaserScan(late); }), "outside the int32 seconds"));
}

TEST(RosMessageDefinition, ListsTheFieldsThenEachDependencyOnce) {
  const std::string separator = std::string(80, '=') + "\n";
  const std::string scan(RosMessageDefinition("sensor_msgs/msg/LaserScan"));
  EXPECT_EQ(scan.rfind("std_msgs/Header header\nfloat32 angle_min\n", 0), 0u) << scan;
  EXPECT_TRUE(Contains(scan, "float32[] ranges\nfloat32[] intensities\n" + separator +
                                 "MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\n"
                                 "string frame_id\n" +
                                 separator +
                                 "MSG: builtin_interfaces/Time\nint32 sec\n"
                                 "uint32 nanosec\n"))
      << scan;

  const std::string odom(RosMessageDefinition("nav_msgs/msg/Odometry"));
  for (const char* dep :
       {"std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/PoseWithCovariance",
        "geometry_msgs/Pose", "geometry_msgs/Point", "geometry_msgs/Quaternion",
        "geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist", "geometry_msgs/Vector3"}) {
    const std::string line = separator + "MSG: " + dep + "\n";
    const std::size_t at = odom.find(line);
    EXPECT_NE(at, std::string::npos) << dep;
    EXPECT_EQ(odom.find(line, at + 1), std::string::npos) << dep << " twice";
  }
  EXPECT_TRUE(Contains(odom, "float64[36] covariance\n"));

  const std::string tf(RosMessageDefinition("tf2_msgs/msg/TFMessage"));
  EXPECT_EQ(tf.rfind("geometry_msgs/TransformStamped[] transforms\n" + separator +
                         "MSG: geometry_msgs/TransformStamped\n",
                     0),
            0u)
      << tf;
  EXPECT_TRUE(Contains(tf, "MSG: geometry_msgs/Transform\n"));
  EXPECT_TRUE(Contains(tf, "MSG: geometry_msgs/Quaternion\nfloat64 x 0\n"));

  const std::string pose(RosMessageDefinition("geometry_msgs/msg/PoseStamped"));
  EXPECT_EQ(pose.rfind("std_msgs/Header header\ngeometry_msgs/Pose pose\n" + separator, 0), 0u);
  EXPECT_FALSE(Contains(pose, "Twist"));

  EXPECT_TRUE(RosMessageDefinition("std_msgs/msg/String").empty());
  EXPECT_TRUE(RosMessageDefinition("sensor_msgs/LaserScan").empty());
}

}  // namespace ros_messages_test
}  // namespace retrace::logs
