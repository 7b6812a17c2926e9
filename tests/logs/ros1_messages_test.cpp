#include "logs/ros1_messages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "logs/raw_message.hpp"
#include "logs/ros1_serialization.hpp"
#include "logs/ros_messages.hpp"
#include "logs/stream_messages.hpp"
#include "tests/support/io_error_of.hpp"

namespace retrace::logs {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace ros1_messages_test {

using Buffer = std::vector<std::uint8_t>;
using testing::IoErrorOf;
constexpr float kInf = std::numeric_limits<float>::infinity();

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
  m.scan.ranges = {1.0f, kInf, -kInf, 2.5f, 0.0f, 29.75f, 12.0f, 13.0f, 14.0f, 15.0f, 16.0f, 17.0f};
  return m;
}

// Every proper prefix of a message is refused with the type's name, and so is a trailing byte.
template <typename Decode>
void ExpectPrefixesAndTrailingBytesRefused(const Buffer& full, Decode decode,
                                           const std::string& type) {
  for (std::size_t n = 0; n < full.size(); ++n) {
    const Buffer prefix(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(n));
    const std::string error = IoErrorOf([&] { decode(prefix); });
    EXPECT_TRUE(Contains(error, type + ": ")) << "prefix " << n << ": '" << error << "'";
  }
  Buffer longer = full;
  longer.push_back(0);
  EXPECT_TRUE(
      Contains(IoErrorOf([&] { decode(longer); }), type + ": 1 bytes after the last field"));
}

// The header of a ROS 1 message: seq, stamp, frame_id.
void WriteHeader(Ros1Writer& w, Ros1Time stamp, const std::string& frame) {
  w.Write<std::uint32_t>(7);
  w.WriteTime(stamp);
  w.WriteString(frame);
}

// A sensor_msgs/MultiEchoLaserScan: beams with two echoes, none and one.
Buffer MultiEchoScan() {
  Ros1Writer w;
  WriteHeader(w, {100, 500'000'000}, "laser");
  for (float v : {-0.5f, 0.5f, 0.5f, 0.0f, 0.1f, 0.2f, 40.0f}) w.Write<float>(v);
  w.WriteSequenceLength(3);  // ranges: LaserEcho[]
  w.WriteFloat32Sequence(std::vector<float>{2.0f, 7.0f});
  w.WriteFloat32Sequence(std::vector<float>{});
  w.WriteFloat32Sequence(std::vector<float>{3.5f});
  w.WriteSequenceLength(3);  // intensities
  for (int i = 0; i < 3; ++i) w.WriteFloat32Sequence(std::vector<float>{1.0f});
  return w.Take();
}

// A geometry_msgs/PoseWithCovarianceStamped at (1, 2) facing 90 degrees.
Buffer PoseWithCovariance() {
  Ros1Writer w;
  WriteHeader(w, {12, 250'000'000}, "map");
  const double h = std::sqrt(0.5);
  for (double v : {1.0, 2.0, 0.5, 0.0, 0.0, h, h}) w.Write<double>(v);
  for (int i = 0; i < 36; ++i) w.Write<double>(0.01 * i);
  return w.Take();
}

TEST(Ros1Serialization, TimesRoundToTheNanosecondAndStayInUint32Seconds) {
  const Ros1Time t = ToRos1Time(1585866235.25);
  EXPECT_EQ(t.sec, 1585866235U);
  EXPECT_EQ(t.nsec, 250'000'000U);
  EXPECT_EQ(ToRos1Time(1.9999999999).sec, 2U);  // rounds up into the next second
  EXPECT_EQ(ToRos1Time(1.9999999999).nsec, 0U);
  EXPECT_DOUBLE_EQ(Ros1StampSeconds({3, 500'000'000}), 3.5);
  EXPECT_TRUE(Contains(IoErrorOf([] { ToRos1Time(-1.0); }), "uint32 seconds of ROS 1 time"));
  EXPECT_TRUE(Contains(IoErrorOf([] { ToRos1Time(5e9); }), "uint32 seconds of ROS 1 time"));
  EXPECT_TRUE(Contains(IoErrorOf([] { ToRos1Time(std::nan("")); }), "not finite"));
}

TEST(Ros1Serialization, StringsHaveNoTerminatorAndCountsAreCheckedBeforeAllocating) {
  Ros1Writer w;
  w.WriteString("odom");
  const Buffer b = w.Take();
  EXPECT_EQ(b, (Buffer{4, 0, 0, 0, 'o', 'd', 'o', 'm'}));
  Ros1Reader r(b);
  EXPECT_EQ(r.ReadString(), "odom");
  EXPECT_EQ(r.remaining(), 0U);

  const Buffer huge_count = {0xff, 0xff, 0xff, 0x7f, 0, 0, 0, 0};
  EXPECT_TRUE(Contains(IoErrorOf([&] { Ros1Reader(huge_count).ReadFloat32Sequence(); }),
                       "array of 2147483647 elements at byte 0 needs at least"));
  EXPECT_TRUE(Contains(IoErrorOf([&] { Ros1Reader(huge_count).ReadString(); }),
                       "string length 2147483647 at byte 0 beyond the end"));
}

TEST(Ros1MessageCodec, LaserScanRoundTripsAndChecksItsAngles) {
  const ScanMessage in = SampleScan();
  const Buffer bytes = EncodeRos1LaserScan(in);
  const ScanMessage out = DecodeRos1LaserScan(bytes);
  EXPECT_EQ(out.frame_id, "laser");
  EXPECT_DOUBLE_EQ(out.scan.stamp, in.scan.stamp);
  EXPECT_EQ(out.scan.angle_min, -1.5);
  EXPECT_EQ(out.scan.angle_increment, 0.25);
  EXPECT_EQ(out.scan.range_min, 0.125);
  EXPECT_EQ(out.scan.range_max, 30.0);
  EXPECT_EQ(out.scan.ranges, in.scan.ranges);
  EXPECT_FALSE(out.angle_max.has_value());
  // seq, stamp, frame_id, 7 float32s, two arrays: no padding anywhere.
  EXPECT_EQ(bytes.size(), 4 + 8 + 4 + 5 + 7 * 4 + 4 + 4 * in.scan.ranges.size() + 4);
  ExpectPrefixesAndTrailingBytesRefused(
      bytes, [](const Buffer& b) { DecodeRos1LaserScan(b); }, "sensor_msgs/LaserScan");

  // angle_max far from the last beam is refused as in ROS 2.
  Buffer off = bytes;
  const float angle_max = 5.0f;
  std::memcpy(off.data() + 4 + 8 + 4 + 5 + 4, &angle_max, 4);
  EXPECT_TRUE(Contains(IoErrorOf([&] { DecodeRos1LaserScan(off); }),
                       "sensor_msgs/LaserScan: angle_max 5 does not match"));
}

TEST(Ros1MessageCodec, MultiEchoScanTakesTheFirstEchoOfEachBeam) {
  const Buffer bytes = MultiEchoScan();
  const ScanMessage m = DecodeRos1MultiEchoLaserScan(bytes);
  EXPECT_EQ(m.frame_id, "laser");
  EXPECT_DOUBLE_EQ(m.scan.stamp, 100.5);
  EXPECT_EQ(m.scan.angle_min, -0.5);
  EXPECT_EQ(m.scan.angle_increment, 0.5);
  EXPECT_EQ(m.scan.range_max, 40.0);
  // Two echoes: the first; none: no return; one: that one.
  EXPECT_EQ(m.scan.ranges, (std::vector<float>{2.0f, kInf, 3.5f}));
  EXPECT_TRUE(m.scan.NoReturn(1));
  ExpectPrefixesAndTrailingBytesRefused(
      bytes, [](const Buffer& b) { DecodeRos1MultiEchoLaserScan(b); },
      "sensor_msgs/MultiEchoLaserScan");
}

TEST(Ros1MessageCodec, OdometryTfAndPosesRoundTripOnThePlane) {
  const core::Pose2 X(1.5, -2.25, 0.75);
  const Buffer odom = EncodeRos1Odometry({12.5, "odom", "base_link", X}, {0.5, 0.1});
  const OdometryMessage o = DecodeRos1Odometry(odom);
  EXPECT_EQ(o.frame_id, "odom");
  EXPECT_EQ(o.child_frame_id, "base_link");
  EXPECT_DOUBLE_EQ(o.stamp, 12.5);
  EXPECT_EQ(o.pose.x, 1.5);
  EXPECT_EQ(o.pose.y, -2.25);
  EXPECT_NEAR(o.pose.theta, 0.75, 1e-15);
  ExpectPrefixesAndTrailingBytesRefused(
      odom, [](const Buffer& b) { DecodeRos1Odometry(b); }, "nav_msgs/Odometry");

  const TfMessage tf_in{{{1.0, "odom", "base_link", X}, {2.0, "base_link", "laser", X}}};
  const Buffer tf = EncodeRos1TfMessage(tf_in);
  const TfMessage tf_out = DecodeRos1TfMessage(tf);
  ASSERT_EQ(tf_out.transforms.size(), 2U);
  EXPECT_EQ(tf_out.transforms[1].parent, "base_link");
  EXPECT_EQ(tf_out.transforms[1].child, "laser");
  EXPECT_DOUBLE_EQ(tf_out.transforms[1].stamp, 2.0);
  EXPECT_NEAR(tf_out.transforms[1].X_PC.theta, 0.75, 1e-15);
  ExpectPrefixesAndTrailingBytesRefused(
      tf, [](const Buffer& b) { DecodeRos1TfMessage(b, kRos1LegacyTfMessageType); },
      "tf/tfMessage");

  const PoseStampedMessage p = DecodeRos1PoseStamped(EncodeRos1PoseStamped({3.0, "world", X}));
  EXPECT_EQ(p.frame_id, "world");
  EXPECT_EQ(p.pose.x, 1.5);

  const PoseStampedMessage c = DecodeRos1PoseWithCovarianceStamped(PoseWithCovariance());
  EXPECT_EQ(c.frame_id, "map");
  EXPECT_DOUBLE_EQ(c.stamp, 12.25);
  EXPECT_EQ(c.pose.x, 1.0);
  EXPECT_EQ(c.pose.y, 2.0);
  EXPECT_NEAR(c.pose.theta, std::numbers::pi / 2, 1e-15);
  ExpectPrefixesAndTrailingBytesRefused(
      PoseWithCovariance(), [](const Buffer& b) { DecodeRos1PoseWithCovarianceStamped(b); },
      "geometry_msgs/PoseWithCovarianceStamped");
}

TEST(Ros1MessageCodec, TfCountBeyondTheBytesIsRefusedBeforeAllocating) {
  const Buffer b = {0x00, 0x00, 0x00, 0x10};  // 2^28 transforms in 0 bytes
  EXPECT_TRUE(Contains(IoErrorOf([&] { DecodeRos1TfMessage(b); }),
                       "tf2_msgs/TFMessage: array of 268435456 elements"));
}

TEST(Ros1Types, KnownByNameAndMd5sum) {
  EXPECT_EQ(Ros1TypeMd5("sensor_msgs/LaserScan"), "90c7ef2dc6895d81024acba2ac42f369");
  EXPECT_EQ(Ros1TypeMd5("tf/tfMessage"), Ros1TypeMd5("tf2_msgs/TFMessage"));
  EXPECT_EQ(Ros1TypeMd5("std_msgs/String"), "");
  EXPECT_NO_THROW(RequireRos1Md5("nav_msgs/Odometry", "cd5e73d190d741a2f92e81eda573aca7"));
  const std::string error = IoErrorOf(
      [] { RequireRos1Md5("sensor_msgs/LaserScan", "0123456789abcdef0123456789abcdef"); });
  EXPECT_EQ(error,
            "sensor_msgs/LaserScan: md5sum '0123456789abcdef0123456789abcdef' is not the md5sum of "
            "the sensor_msgs/LaserScan retrace reads (90c7ef2dc6895d81024acba2ac42f369): another "
            "definition of the type");
  EXPECT_TRUE(Contains(IoErrorOf([] { RequireRos1Md5("sensor_msgs/LaserScan", "*"); }), "'*'"));
}

TEST(Ros1Types, DefinitionsHoldTheirDependencies) {
  const std::string odometry(Ros1MessageDefinition("nav_msgs/Odometry"));
  EXPECT_TRUE(odometry.starts_with("Header header\nstring child_frame_id\n"));
  EXPECT_TRUE(Contains(odometry, std::string(80, '=') + "\nMSG: std_msgs/Header\nuint32 seq\n"));
  EXPECT_TRUE(Contains(odometry, "MSG: geometry_msgs/TwistWithCovariance\n"));
  EXPECT_TRUE(Contains(odometry, "MSG: geometry_msgs/Vector3\n"));
  EXPECT_TRUE(Contains(std::string(Ros1MessageDefinition("sensor_msgs/MultiEchoLaserScan")),
                       "MSG: sensor_msgs/LaserEcho\nfloat32[] echoes\n"));
  EXPECT_EQ(Ros1MessageDefinition("std_msgs/String"), "");
}

// A raw ROS 1 message of `type` with its md5sum.
RawMessage Ros1Raw(std::string_view type, const Buffer& data, std::string_view md5 = {}) {
  RawMessage m;
  m.topic = "/x";
  m.type = type;
  m.encoding = "ros1";
  m.md5sum = md5.empty() ? Ros1TypeMd5(type) : md5;
  m.data = data;
  return m;
}

TEST(StreamMessages, Ros1TypesFeedTheStreamsOfTheirRos2Twins) {
  EXPECT_EQ(StreamKindOf("ros1", "sensor_msgs/LaserScan"), StreamKind::kScan);
  EXPECT_EQ(StreamKindOf("ros1", "sensor_msgs/MultiEchoLaserScan"), StreamKind::kScan);
  EXPECT_EQ(StreamKindOf("cdr", "sensor_msgs/msg/LaserScan"), StreamKind::kScan);
  EXPECT_EQ(StreamKindOf("ros1", "nav_msgs/Odometry"), StreamKind::kOdometry);
  EXPECT_EQ(StreamKindOf("ros1", "tf/tfMessage"), StreamKind::kTf);
  EXPECT_EQ(StreamKindOf("ros1", "tf2_msgs/TFMessage"), StreamKind::kTf);
  EXPECT_EQ(StreamKindOf("ros1", "geometry_msgs/PoseWithCovarianceStamped"), StreamKind::kPose);
  // Each ROS by its own names only.
  EXPECT_EQ(StreamKindOf("cdr", "sensor_msgs/LaserScan"), StreamKind::kNone);
  EXPECT_EQ(StreamKindOf("ros1", "sensor_msgs/msg/LaserScan"), StreamKind::kNone);
  EXPECT_EQ(StreamKindOf("carmen", "FLASER"), StreamKind::kNone);
  EXPECT_EQ(StreamTypeNames(StreamKind::kScan, true),
            "sensor_msgs/LaserScan or MultiEchoLaserScan");
  EXPECT_EQ(StreamTypeNames(StreamKind::kScan, false), "sensor_msgs/msg/LaserScan");

  const Buffer scan = EncodeRos1LaserScan(SampleScan());
  EXPECT_EQ(DecodeStreamScan(Ros1Raw("sensor_msgs/LaserScan", scan)).scan.ranges,
            SampleScan().scan.ranges);
  const Buffer echoes = MultiEchoScan();
  EXPECT_EQ(DecodeStreamScan(Ros1Raw("sensor_msgs/MultiEchoLaserScan", echoes)).scan.size(), 3U);
  const Buffer pose = PoseWithCovariance();
  EXPECT_EQ(DecodeStreamPose(Ros1Raw("geometry_msgs/PoseWithCovarianceStamped", pose)).frame_id,
            "map");
  const Buffer tf = EncodeRos1TfMessage({{{1.0, "odom", "base_link", core::Pose2()}}});
  EXPECT_EQ(DecodeStreamTf(Ros1Raw("tf/tfMessage", tf)).transforms.size(), 1U);

  // Another definition under a known name is refused, naming it; so is a message of another
  // stream.
  EXPECT_TRUE(Contains(IoErrorOf([&] {
                         DecodeStreamScan(Ros1Raw("sensor_msgs/LaserScan", scan,
                                                  "ffffffffffffffffffffffffffffffff"));
                       }),
                       "sensor_msgs/LaserScan: md5sum 'ffffffffffffffffffffffffffffffff' is not"));
  EXPECT_TRUE(Contains(IoErrorOf([&] { DecodeStreamOdometry(Ros1Raw("tf/tfMessage", tf)); }),
                       "not a message of the odometry"));
}

}  // namespace ros1_messages_test
}  // namespace retrace::logs
