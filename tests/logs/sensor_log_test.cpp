#include "logs/sensor_log.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "logs/carmen_writer.hpp"
#include "logs/log_source.hpp"
#include "logs/mcap_writer.hpp"
#include "logs/ros1_bag_writer.hpp"
#include "logs/ros1_messages.hpp"
#include "logs/ros1_serialization.hpp"
#include "logs/ros_messages.hpp"
#include "tests/support/io_error_of.hpp"
#include "tests/support/mocap_bag.hpp"
#include "tests/support/ros1_bag_builder.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::logs {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace sensor_log_test {

namespace fs = std::filesystem;

// A drive along x at 1 m/s for 5 s: odometry at 50 Hz (drifting 1 % long), scans at 10 Hz, the
// truth and a LiDAR 0.2 m ahead of the base.
const core::Pose2 kMount(0.2, 0.0, 0.0);
core::Pose2 Truth(double t) { return {t, 0.5 * std::sin(t), 0.1 * t}; }
core::Pose2 Odometry(double t) { return {1.01 * t, 0.5 * std::sin(t), 0.1 * t}; }
core::LaserScan Scan(double t) {
  core::LaserScan scan;
  scan.stamp = t;
  scan.angle_min = -1.5;
  scan.angle_increment = 0.01;
  scan.range_min = 0.1;
  scan.range_max = 20.0;
  for (int i = 0; i < 301; ++i) scan.ranges.push_back(3.0f + 0.001f * static_cast<float>(i));
  scan.ranges[7] = std::numeric_limits<float>::infinity();
  return scan;
}

fs::path WriteCarmen(const fs::path& file) {
  CarmenWriter w(file);
  for (int k = 0; k <= 250; ++k) {
    const double t = 0.02 * k;
    w.WriteOdometry(t, Odometry(t), 1.0, 0.1);
    w.WriteTruePose(t, Truth(t), Odometry(t));
    if (k % 5 == 0) w.WriteLaser(Scan(t), Odometry(t), kMount, 1.0, 0.1);
  }
  w.Close();
  return file;
}

// An MCAP bag as `retrace run --record-log` writes one, with `scan_topics` LaserScan topics and,
// if `odometry_topic`, a nav_msgs/Odometry topic (else tf only).
fs::path WriteMcap(const fs::path& file, std::vector<std::string> scan_topics = {"/scan"},
                   bool odometry_topic = true) {
  McapWriter w(file, McapCompression::kZstd);
  std::vector<std::uint16_t> scans;
  for (const std::string& topic : scan_topics)
    scans.push_back(w.AddChannel(topic, "sensor_msgs/msg/LaserScan"));
  const std::uint16_t odom = w.AddChannel("/odom", "nav_msgs/msg/Odometry");
  const std::uint16_t tf = w.AddChannel("/tf", "tf2_msgs/msg/TFMessage");
  const std::uint16_t tf_static = w.AddChannel("/tf_static", "tf2_msgs/msg/TFMessage");
  const std::uint16_t truth = w.AddChannel("/ground_truth", "geometry_msgs/msg/PoseStamped");
  // The mount through a chain: base_link -> laser_mount -> laser.
  TfMessage mount{{{0.0, "base_link", "laser_mount", core::Pose2(0.1, 0.0, 0.0)},
                   {0.0, "laser_mount", "laser", core::Pose2(0.1, 0.0, 0.0)}}};
  w.Write(tf_static, 0, EncodeTfMessage(mount));
  for (int k = 0; k <= 250; ++k) {
    const double t = 0.02 * k;
    const auto ns = static_cast<std::int64_t>(std::llround(t * 1e9));
    if (odometry_topic) w.Write(odom, ns, EncodeOdometry({t, "odom", "base_link", Odometry(t)}));
    w.Write(tf, ns, EncodeTfMessage({{{t, "odom", "base_link", Odometry(t)}}}));
    w.Write(truth, ns, EncodePoseStamped({t, "world", Truth(t)}));
    if (k % 5 == 0) {
      for (std::uint16_t channel : scans) w.Write(channel, ns, EncodeLaserScan({Scan(t), "laser"}));
    }
  }
  w.Close();
  return file;
}

// The same drive as WriteMcap as a ROS 1 bag: tf through tf/tfMessage (the old tf package's
// name), and with `multi_echo`, the scans as sensor_msgs/MultiEchoLaserScan (each beam's range
// then a farther second echo) and the reference as a PoseWithCovarianceStamped on /amcl_pose.
fs::path WriteRos1Bag(const fs::path& file, bool multi_echo = false, bool close = true) {
  Ros1BagWriter w(file, Ros1BagCompression::kLz4, 16 * 1024);
  const std::uint32_t scan = w.AddConnection(
      "/scan", multi_echo ? "sensor_msgs/MultiEchoLaserScan" : "sensor_msgs/LaserScan");
  const std::uint32_t odom = w.AddConnection("/odom", "nav_msgs/Odometry");
  const std::uint32_t tf = w.AddConnection("/tf", "tf/tfMessage");
  const std::uint32_t tf_static = w.AddConnection("/tf_static", "tf2_msgs/TFMessage");
  const std::uint32_t truth =
      multi_echo ? w.AddConnection("/amcl_pose", "geometry_msgs/PoseWithCovarianceStamped")
                 : w.AddConnection("/ground_truth", "geometry_msgs/PoseStamped");
  TfMessage mount{{{0.0, "base_link", "laser_mount", core::Pose2(0.1, 0.0, 0.0)},
                   {0.0, "laser_mount", "laser", core::Pose2(0.1, 0.0, 0.0)}}};
  w.Write(tf_static, 0, EncodeRos1TfMessage(mount));
  if (multi_echo) {  // one pose set in rviz: not a reference
    const std::uint32_t initial = w.AddConnection("/initialpose", "geometry_msgs/PoseStamped");
    w.Write(initial, 0, EncodeRos1PoseStamped({0.0, "map", Truth(0.0)}));
  }
  for (int k = 0; k <= 250; ++k) {
    const double t = 0.02 * k;
    const auto ns = static_cast<std::int64_t>(std::llround(t * 1e9));
    w.Write(odom, ns, EncodeRos1Odometry({t, "odom", "base_link", Odometry(t)}));
    w.Write(tf, ns, EncodeRos1TfMessage({{{t, "odom", "base_link", Odometry(t)}}}));
    if (!multi_echo) {
      w.Write(truth, ns, EncodeRos1PoseStamped({t, "world", Truth(t)}));
    } else {
      Ros1Writer p;  // geometry_msgs/PoseWithCovarianceStamped
      p.Write<std::uint32_t>(0);
      p.WriteTime(ToRos1Time(t));
      p.WriteString("map");
      const core::Pose2 X = Truth(t);
      p.WriteFloat64Array(std::vector<double>{X.x, X.y, 0.0, 0.0, 0.0, std::sin(0.5 * X.theta),
                                               std::cos(0.5 * X.theta)});
      p.WriteFloat64Array(std::vector<double>(36, 0.0));
      w.Write(truth, ns, p.Take());
    }
    if (k % 5 != 0) continue;
    if (!multi_echo) {
      w.Write(scan, ns, EncodeRos1LaserScan({Scan(t), "laser"}));
      continue;
    }
    const core::LaserScan s = Scan(t);
    Ros1Writer e;  // sensor_msgs/MultiEchoLaserScan
    e.Write<std::uint32_t>(0);
    e.WriteTime(ToRos1Time(t));
    e.WriteString("laser");
    const double angle_max = s.Angle(s.size() - 1);
    for (double v : {s.angle_min, angle_max, s.angle_increment, 0.0, 0.0, s.range_min, s.range_max})
      e.Write<float>(static_cast<float>(v));
    e.WriteSequenceLength(static_cast<std::uint32_t>(s.size()));
    for (float r : s.ranges) e.WriteFloat32Sequence(std::vector<float>{r, r + 1.0f});
    e.WriteSequenceLength(0);
    w.Write(scan, ns, e.Take());
  }
  if (close) w.Close();
  return file;
}

std::string IndexError(const fs::path& file, const StreamChoice& choice = {}) {
  try {
    const LogIndex index = IndexLog(file, choice);
    RequireUsable(index);
  } catch (const core::IoError& e) {
    return e.what();
  }
  return "";
}

void ExpectNear(const core::Pose2& a, const core::Pose2& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(core::AngleDiff(a.theta, b.theta), 0.0, tol);
}

TEST(SensorLog, CarmenStreamsAreFoundAndRead) {
  testing::TempDir tmp;
  const LogIndex index = IndexLog(WriteCarmen(tmp.path() / "drive.log.gz"));
  EXPECT_EQ(index.problem, "");
  EXPECT_EQ(index.format, LogFormat::kCarmen);
  EXPECT_EQ(index.scan_topic, "ROBOTLASER1");
  EXPECT_EQ(index.scan.scans, 51U);
  EXPECT_EQ(index.scan.beams, 301U);
  EXPECT_EQ(index.scan.angle_increment, 0.01);
  EXPECT_NEAR(index.scan.field_of_view(), 3.0, 1e-12);
  // The laser lines carry the robot's pose exactly at each scan: that is the odometry.
  EXPECT_NE(index.odometry_source.find("ROBOTLASER1"), std::string::npos);
  ASSERT_EQ(index.odometry.size(), 51U);
  ExpectNear(index.odometry[10].pose, Odometry(1.0), 1e-9);
  ASSERT_EQ(index.reference.size(), 251U);
  ExpectNear(index.reference[100].pose, Truth(2.0), 1e-9);
  ExpectNear(index.X_RL, kMount, 1e-9);
  EXPECT_NEAR(index.duration_s(), 5.0, 1e-9);

  std::vector<double> stamps;
  ReadScans(index, 1.0, 2.0, [&](const ScanMessage& m, double t) {
    EXPECT_NEAR(t, m.scan.stamp, 1e-9);
    EXPECT_EQ(m.scan.ranges[100], Scan(0).ranges[100]);  // bit for bit
    EXPECT_TRUE(m.scan.NoReturn(7));
    stamps.push_back(m.scan.stamp);
  });
  ASSERT_EQ(stamps.size(), 11U);
  EXPECT_NEAR(stamps.front(), 1.0, 1e-9);
  EXPECT_NEAR(stamps.back(), 2.0, 1e-9);
}

TEST(SensorLog, McapStreamsMountChainAndTfOdometry) {
  testing::TempDir tmp;
  const LogIndex index = IndexLog(WriteMcap(tmp.path() / "drive.mcap"));
  EXPECT_EQ(index.problem, "");
  EXPECT_EQ(index.format, LogFormat::kMcap);
  EXPECT_EQ(index.scan_topic, "/scan");
  EXPECT_EQ(index.laser_frame, "laser");
  EXPECT_EQ(index.base_frame, "base_link");
  ExpectNear(index.X_RL, core::Pose2(0.2, 0.0, 0.0), 1e-12);  // through laser_mount
  EXPECT_NE(index.mount_source.find("tf_static"), std::string::npos);
  EXPECT_NE(index.odometry_source.find("/odom"), std::string::npos);
  ASSERT_EQ(index.odometry.size(), 251U);
  ExpectNear(index.odometry[50].pose, Odometry(1.0), 1e-9);
  EXPECT_NE(index.reference_source.find("/ground_truth"), std::string::npos);
  ExpectNear(index.reference[250].pose, Truth(5.0), 1e-9);

  // Without the Odometry topic the odometry comes from tf odom -> base_link.
  const LogIndex tf = IndexLog(WriteMcap(tmp.path() / "tf.mcap", {"/scan"}, false));
  EXPECT_EQ(tf.problem, "");
  EXPECT_EQ(tf.odometry_source, "tf odom -> base_link");
  ExpectNear(tf.odometry[50].pose, Odometry(1.0), 1e-9);
  // ... from the frame named with --odom-frame only: from 'map', the log has no odometry.
  StreamChoice other;
  other.odom_frame = "map";
  const LogIndex map = IndexLog(tmp.path() / "tf.mcap", other);
  EXPECT_TRUE(map.odometry.empty());
  EXPECT_EQ(map.odometry_missing, "no nav_msgs/msg/Odometry topic, no tf from 'map'");
}

// A bag recorded under motion capture: scans and a PoseStamped topic, no odometry. It is usable
// (odometry can be drawn from the reference); the index says what is missing and still finds
// the mount, from the top of the scans' static chain.
TEST(SensorLog, ABagWithoutOdometryIsUsableAndSaysWhatIsMissing) {
  testing::TempDir tmp;
  const LogIndex index = IndexLog(testing::WriteMocapBag(tmp.path() / "mocap.mcap"));
  EXPECT_EQ(index.problem, "");
  EXPECT_NO_THROW(RequireUsable(index));
  EXPECT_TRUE(index.odometry.empty());
  EXPECT_EQ(index.odometry_source, "");
  EXPECT_EQ(index.odometry_missing, "no nav_msgs/msg/Odometry topic, no tf from 'odom'");
  EXPECT_EQ(index.reference_topic, "/pose");
  EXPECT_EQ(index.reference.size(), 301U);
  EXPECT_EQ(index.scan.scans, 61U);
  EXPECT_EQ(index.base_frame, "base_link");
  ExpectNear(index.X_RL, testing::kMocapMount, 1e-12);
  EXPECT_EQ(index.mount_source,
            "tf_static base_link -> laser (the top of the scans' static chain: no odometry names "
            "the base; --base-frame chooses another)");
  EXPECT_TRUE(index.notes.empty());
}

// A CARMEN log whose laser lines carry no robot pose, without ODOM lines, is the same: usable,
// its TRUEPOS lines the reference; lines named with --odometry-topic that it lacks are an error.
TEST(SensorLog, ACarmenLogWithoutOdometryIsUsableAndSaysWhatIsMissing) {
  testing::TempDir tmp;
  std::string text;
  for (int k = 0; k < 20; ++k) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "RAWLASER1 0 -1.5 3.0 1.5 20.0 0.01 0 3 1.0 2.0 3.0 0 %.1f host %.1f\n"
                  "TRUEPOS %.1f 0 0 0 0 0 %.1f host %.1f\n",
                  0.1 * k, 0.1 * k, 0.1 * k, 0.1 * k, 0.1 * k);
    text += line;
  }
  const fs::path file = tmp.Write("raw.log", text);
  const LogIndex index = IndexLog(file);
  EXPECT_EQ(index.problem, "");
  EXPECT_TRUE(index.odometry.empty());
  EXPECT_EQ(index.odometry_missing, "no ODOM lines, RAWLASER1 lines carry no robot pose");
  EXPECT_EQ(index.reference_topic, "TRUEPOS");
  StreamChoice odom;
  odom.odometry_topic = "ODOM";
  EXPECT_EQ(IndexError(file, odom), file.string() + ": no odometry in 'ODOM' lines");
}

TEST(SensorLog, SeveralScanTopicsNeedAChoice) {
  testing::TempDir tmp;
  const fs::path bag = WriteMcap(tmp.path() / "two.mcap", {"/front", "/rear"});
  const std::string error = IndexError(bag);
  EXPECT_NE(error.find("several topics hold laser scans"), std::string::npos) << error;
  EXPECT_NE(error.find("/front, /rear"), std::string::npos) << error;
  EXPECT_NE(error.find("--scan-topic"), std::string::npos) << error;
  // The log is still described: both scan topics, and the streams that need no choice.
  const LogIndex index = IndexLog(bag);
  EXPECT_EQ(index.topics.size(), 6U);
  EXPECT_TRUE(index.needs_choice);
  ASSERT_EQ(index.scan_streams.size(), 2U);
  EXPECT_EQ(index.scan_streams[0].topic, "/front");
  EXPECT_EQ(index.scan_streams[1].topic, "/rear");
  EXPECT_EQ(index.scan_streams[1].geometry.scans, 51U);
  EXPECT_EQ(index.scan_streams[1].geometry.beams, 301U);
  EXPECT_EQ(index.scan_streams[1].frame, "laser");
  EXPECT_EQ(index.odometry.size(), 251U);
  EXPECT_NE(index.reference_source.find("/ground_truth"), std::string::npos);

  StreamChoice choice;
  choice.scan_topic = "/rear";
  EXPECT_EQ(IndexError(bag, choice), "");
  choice.scan_topic = "/odom";
  EXPECT_NE(IndexError(bag, choice).find("holds no laser scans"), std::string::npos);
  choice.scan_topic = "/nope";
  EXPECT_NE(IndexError(bag, choice).find("is not in the log"), std::string::npos);
}

// A bag whose driver writes angle_max = angle_min + n * increment (one increment too far), in
// every scan: used, with one note for the log, not one per scan.
TEST(SensorLog, AngleMaxOffByAnIncrementIsNotedOncePerLog) {
  testing::TempDir tmp;
  const fs::path file = tmp.path() / "angle_max.mcap";
  {
    McapWriter w(file, McapCompression::kNone);
    const std::uint16_t scans = w.AddChannel("/scan", "sensor_msgs/msg/LaserScan");
    const std::uint16_t odom = w.AddChannel("/odom", "nav_msgs/msg/Odometry");
    for (int k = 0; k <= 50; ++k) {
      const double t = 0.1 * k;
      const auto ns = static_cast<std::int64_t>(std::llround(t * 1e9));
      w.Write(odom, ns, EncodeOdometry({t, "odom", "laser", Odometry(t)}));
      std::vector<std::uint8_t> cdr = EncodeLaserScan({Scan(t), "laser"});
      // angle_max, the second float after the header (stamp 8 bytes, frame "laser": 4 + 6,
      // padded to 4): at 4 + 8 + 12 + 4 = 28 from the start.
      const float angle_max = static_cast<float>(-1.5 + 301 * 0.01);
      std::memcpy(cdr.data() + 28, &angle_max, sizeof angle_max);
      w.Write(scans, ns, cdr);
    }
    w.Close();
  }
  const LogIndex index = IndexLog(file);
  EXPECT_EQ(index.problem, "");
  EXPECT_EQ(index.scan.scans, 51U);
  EXPECT_EQ(index.scan.inconsistent_angle_max, 51U);
  ASSERT_EQ(index.notes.size(), 1U);
  const std::string& note = index.notes[0];
  EXPECT_NE(note.find("'/scan': angle_max of 51 of 51 scans is 1 increments from angle_min + "
                      "(n - 1) * angle_increment (the first, message 2: 1.51 rad for 1.5 rad)"),
            std::string::npos)
      << note;
  EXPECT_NE(note.find("beam i is taken at angle_min + i * angle_increment"), std::string::npos);
  ReadScans(index, 0.0, 1e9,
            [&](const ScanMessage& m, double) { EXPECT_NEAR(m.scan.Angle(300), 1.5, 1e-6); });
}

// The CARMEN lines of a log whose PARAM lines carry the epoch (logger stamps since 1970) while
// the laser lines carry the logger's own clock: --from and --to count from the first scan, and
// the PARAM lines are named in one note.
TEST(SensorLog, TimesCountFromTheFirstScanAndAnotherClockIsNamed) {
  testing::TempDir tmp;
  std::string text =
      "PARAM robot_front_laser_max 50.0 1134860000.123 host 1134860000.123\n"
      "PARAM laser_front_laser_resolution 1.0 1134860000.124 host 1134860000.124\n";
  for (int k = 0; k <= 50; ++k) {
    const double t = 10.0 + 0.1 * k;
    char line[256];
    std::snprintf(line, sizeof line, "FLASER 3 1.0 2.0 3.0 %.2f 0 0 %.2f 0 0 %.6f host %.6f\n",
                  0.1 * k, 0.1 * k, t, t);
    text += line;
  }
  const fs::path file = tmp.Write("clocks.log", text);
  const LogIndex index = IndexLog(file);
  EXPECT_EQ(index.problem, "");
  EXPECT_EQ(index.origin_ns, 10'000'000'000);
  std::vector<double> times;
  ReadScans(index, 1.0, 2.0, [&](const ScanMessage&, double t) { times.push_back(t); });
  ASSERT_EQ(times.size(), 11U);
  EXPECT_NEAR(times.front(), 1.0, 1e-9);
  ASSERT_EQ(index.topics.size(), 2U);
  EXPECT_NEAR(index.topics[1].first_s, 0.0, 1e-9);  // FLASER
  ASSERT_EQ(index.notes.size(), 1U);
  EXPECT_NE(index.notes[0].find("log times from two clocks: 'PARAM' (2 messages; line 2 at "
                                "11348599"),
            std::string::npos)
      << index.notes[0];
  EXPECT_NE(index.notes[0].find("lie more than 3600 s outside the scans' (0 to 5 s)"),
            std::string::npos)
      << index.notes[0];
}

// CARMEN PARAM lines retrace does not read never refuse a log, whatever their values say: a
// boolean written `no`, free text, a name alone. The ones it reads still refuse a malformed
// value, in one line naming the message and the parameter.
TEST(SensorLog, CarmenParamsRetraceDoesNotReadNeverRefuseTheLog) {
  testing::TempDir tmp;
  const std::string params =
      "PARAM laser_front_laser_flipped no nohost 0\n"
      "PARAM robot_front_laser_max 50.0 nohost 0\n"
      "PARAM robot_allow_rear_motion yes nohost 0\n"
      "PARAM robot_name the blue pioneer nohost 0\n"
      "PARAM logger_comment\n";
  std::string lasers;
  for (int k = 0; k <= 20; ++k) {
    char line[256];
    std::snprintf(line, sizeof line, "FLASER 3 1.0 2.0 60.0 %.1f 0 0 %.1f 0 0 %.1f nohost %.1f\n",
                  0.1 * k, 0.1 * k, 0.1 * k, 0.1 * k);
    lasers += line;
  }
  const LogIndex index = IndexLog(tmp.Write("params.log", params + lasers));
  EXPECT_EQ(index.problem, "");
  EXPECT_EQ(index.scan.scans, 21U);
  EXPECT_EQ(index.scan.range_max, 50.0);  // the parameter it reads is read
  std::size_t scans = 0;
  ReadScans(index, 0.0, 1e9, [&](const ScanMessage& m, double) {
    EXPECT_TRUE(m.scan.NoReturn(2));  // 60 m beyond robot_front_laser_max
    ++scans;
  });
  EXPECT_EQ(scans, 21U);

  const fs::path bad = tmp.Write("bad.log", "PARAM robot_front_laser_max far nohost 0\n" + lasers);
  EXPECT_EQ(IndexError(bad), bad.string() +
                                 ": message 1 on 'PARAM': PARAM robot_front_laser_max: 'far' is "
                                 "not a finite number");
}

// The Intel Research Lab log's lines as a logger printing %g would write them: every scan of the
// drive stamped 1.13486e+09. Refused in one line naming the lines, not "fewer than two
// odometry poses".
TEST(SensorLog, StampsWithTooFewDigitsAreRefusedNamingTheLines) {
  testing::TempDir tmp;
  std::string text = "# written with %g\n";
  for (int k = 0; k < 20; ++k) {
    text += "FLASER 3 1.0 2.0 3.0 " + std::to_string(0.1 * k) + " 0 0 " + std::to_string(0.1 * k) +
            " 0 0 1.13486e+09 nohost 1.13486e+09\n";
  }
  const std::string error = IndexError(tmp.Write("g.log", text));
  EXPECT_NE(error.find("g.log: 19 of 20 scans on 'FLASER' carry the same stamp as the scan before "
                       "them (line 3 to line 21, e.g. 1.13486e+09 s): the stamps were written "
                       "with too few digits"),
            std::string::npos)
      << error;
}

// A corrected log written without time: every stamp 0. Refused in one line that names the way
// out; with --scan-rate (StreamChoice::scan_rate_hz) the scans are stamped by their order, the
// odometry of the laser lines with them and ODOM lines at the last scan's stamp, in both passes.
TEST(SensorLog, ALogWithoutTimeIsRefusedOrGivenNominalStamps) {
  testing::TempDir tmp;
  std::string text = "ODOM 0 0 0 0 0 0 0 nohost 0\n";
  for (int k = 0; k < 20; ++k) {
    const std::string x = std::to_string(0.1 * k);
    text += "FLASER 3 1.0 2.0 3.0 " + x + " 0 0 " + x + " 0 0 0 nohost 0\n";
    text += "ODOM " + x + " 0 0 0 0 0 0 nohost 0\n";
  }
  const fs::path log = tmp.Write("t.log", text);
  EXPECT_EQ(IndexError(log), log.string() +
                                 ": the scans on 'FLASER' carry no time stamps: all 20 are "
                                 "stamped 0 s (line 4 to line 40); give them nominal stamps "
                                 "with --scan-rate HZ");
  StreamChoice choice;
  choice.scan_rate_hz = 4.0;
  const LogIndex index = IndexLog(log, choice);
  ASSERT_EQ(index.problem, "");
  EXPECT_EQ(index.nominal_scan_rate_hz, 4.0);
  EXPECT_EQ(index.scan.scans, 20U);
  EXPECT_DOUBLE_EQ(index.scan.last_stamp, 19 * 0.25);
  ASSERT_EQ(index.odometry.size(), 20U);  // the laser lines' robot poses
  EXPECT_DOUBLE_EQ(index.odometry[8].t, 2.0);
  EXPECT_NEAR(index.odometry[8].pose.x, 0.8, 1e-9);
  int k = 0;
  ReadScans(index, 1.0, 2.0, [&](const ScanMessage& m, double t) {
    EXPECT_DOUBLE_EQ(m.scan.stamp, t);
    EXPECT_DOUBLE_EQ(t, 1.0 + 0.25 * k++);
  });
  EXPECT_EQ(k, 5);
  choice.odometry_topic = "ODOM";
  const LogIndex odom = IndexLog(log, choice);
  ASSERT_EQ(odom.problem, "");
  ASSERT_GE(odom.odometry.size(), 20U);  // the first two both at 0 s
  EXPECT_DOUBLE_EQ(odom.odometry.back().t, 19 * 0.25);
  EXPECT_NEAR(odom.odometry.back().pose.x, 1.9, 1e-9);
}

// ODOM lines stamped since the epoch beside laser lines stamped since the logger started.
TEST(SensorLog, OdometryOnAnotherClockThanTheScansIsRefusedNamingBoth) {
  testing::TempDir tmp;
  std::string text;
  for (int k = 0; k < 20; ++k) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "ODOM %.1f 0 0 0 0 0 %.3f host %.3f\nFLASER 3 1.0 2.0 3.0 %.1f 0 0 %.1f 0 0 "
                  "%.3f host %.3f\n",
                  0.1 * k, 1134860000.0 + 0.1 * k, 0.1 * k, 0.1 * k, 0.1 * k, 0.1 * k, 0.1 * k);
    text += line;
  }
  StreamChoice odom;
  odom.odometry_topic = "ODOM";
  const std::string error = IndexError(tmp.Write("odom.log", text), odom);
  EXPECT_NE(error.find("odom.log: the odometry (ODOM lines, stamps 1134860000 to 1134860001.9 s) "
                       "and the scans (FLASER, stamps 0 to 1.9 s) do not overlap in time: they "
                       "follow two clocks"),
            std::string::npos)
      << error;
}

TEST(SensorLog, TimeGoingBackwardsIsRefusedNamingTheMessage) {
  testing::TempDir tmp;
  const fs::path file = tmp.path() / "back.log";
  {
    CarmenWriter w(file);
    w.WriteOdometry(1.0, core::Pose2(), 0.0, 0.0);
    w.WriteOdometry(2.0, core::Pose2(1, 0, 0), 0.0, 0.0);
    w.WriteOdometry(1.5, core::Pose2(2, 0, 0), 0.0, 0.0);
    w.WriteLaser(Scan(1.0), core::Pose2(), kMount, 0.0, 0.0);
    w.WriteLaser(Scan(2.0), core::Pose2(1, 0, 0), kMount, 0.0, 0.0);
    w.Close();
  }
  // The laser lines carry the odometry: the ODOM lines are not used, and their clock may jitter
  // (the Intel Research Lab log's does).
  EXPECT_EQ(IndexError(file), "");
  StreamChoice odom;
  odom.odometry_topic = "ODOM";
  const std::string error = IndexError(file, odom);
  EXPECT_NE(error.find("back.log: message 3 on 'ODOM'"), std::string::npos) << error;
  EXPECT_NE(error.find("goes back"), std::string::npos) << error;
  EXPECT_NE(error.find("1 of 3 messages go back"), std::string::npos) << error;
}

TEST(SensorLog, AFewStampsGoingBackAreDroppedAndNoted) {
  testing::TempDir tmp;
  const fs::path file = tmp.path() / "jitter.log";
  {
    CarmenWriter w(file);
    for (int k = 0; k < 200; ++k) {
      // One laser line in 200 is stamped 0.05 s before the one before it.
      const double t = k == 100 ? 0.1 * 99 - 0.05 : 0.1 * k;
      w.WriteLaser(Scan(t), core::Pose2(0.1 * k, 0, 0), kMount, 1.0, 0.0);
    }
    w.Close();
  }
  const LogIndex index = IndexLog(file);
  EXPECT_EQ(index.problem, "");
  EXPECT_EQ(index.scan.scans, 199U);
  EXPECT_EQ(index.odometry.size(), 199U);
  ASSERT_EQ(index.notes.size(), 1U);
  EXPECT_NE(index.notes[0].find("1 of 200 messages on 'ROBOTLASER1'"), std::string::npos)
      << index.notes[0];
  std::size_t scans = 0;
  ReadScans(index, 0.0, 1e9, [&](const ScanMessage&, double) { ++scans; });
  EXPECT_EQ(scans, 199U);
}

TEST(SensorLog, FormatsAreDetectedByContent) {
  testing::TempDir tmp;
  EXPECT_EQ(DetectLogFormat(WriteCarmen(tmp.path() / "a.bin")), LogFormat::kCarmen);
  EXPECT_EQ(DetectLogFormat(WriteMcap(tmp.path() / "a.log")), LogFormat::kMcap);
  const fs::path bags = testing::kSource / "tests/data/rosbag2";
  EXPECT_EQ(DetectLogFormat(bags / "talker_sqlite3/talker.db3"), LogFormat::kSqlite);
  EXPECT_EQ(DetectLogFormat(bags / "talker_mcap"), LogFormat::kRosbag2);
  // A rosbag2 folder of either storage gives the same messages.
  for (const char* folder : {"talker_mcap", "talker_sqlite3"}) {
    const std::unique_ptr<MessageSource> source = OpenLog(bags / folder);
    RawMessage m;
    int n = 0;
    while (source->Next(m)) n += m.topic == "/topic";
    EXPECT_EQ(n, 10) << folder;
  }
  const auto error = [](const fs::path& p) {
    try {
      DetectLogFormat(p);
    } catch (const core::IoError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error(tmp.Write("empty.log", "")).find("empty file"), std::string::npos);
  EXPECT_NE(error(tmp.Write("binary.bin", std::string("\x00\x01\x02zz", 5))).find("not a log"),
            std::string::npos);
  fs::create_directories(tmp.path() / "folder");
  EXPECT_NE(error(tmp.path() / "folder").find("without metadata.yaml"), std::string::npos);
  EXPECT_NE(error(tmp.path() / "missing.mcap").find("no such file"), std::string::npos);
}

// `ros2 bag info` users point at the bag's metadata.yaml: it opens the bag, not a CARMEN log.
TEST(SensorLog, ABagsMetadataYamlOpensTheBag) {
  const fs::path metadata = testing::kSource / "tests/data/rosbag2/talker_mcap/metadata.yaml";
  EXPECT_EQ(DetectLogFormat(metadata), LogFormat::kRosbag2);
  const LogIndex index = IndexLog(metadata);
  ASSERT_EQ(index.topics.size(), 2U);
  EXPECT_EQ(index.topics[0].messages + index.topics[1].messages, 20U);
  EXPECT_NE(index.problem.find("no sensor_msgs/msg/LaserScan topic"), std::string::npos);
}

TEST(SensorLog, ABagWithoutScansIsDescribedButNotUsable) {
  const LogIndex index = IndexLog(testing::kSource / "tests/data/rosbag2/talker_mcap");
  EXPECT_EQ(index.topics.size(), 2U);
  EXPECT_NE(index.problem.find("no sensor_msgs/msg/LaserScan topic"), std::string::npos);
  EXPECT_THROW(RequireUsable(index), core::IoError);
}

// A ROS 1 bag gives the streams the MCAP file of the same drive gives, scan for scan.
TEST(SensorLog, Ros1BagGivesTheStreamsOfTheSameMcap) {
  testing::TempDir tmp;
  const LogIndex mcap = IndexLog(WriteMcap(tmp.path() / "drive.mcap"));
  const LogIndex bag = IndexLog(WriteRos1Bag(tmp.path() / "drive.bag"));
  EXPECT_EQ(bag.problem, "");
  EXPECT_EQ(bag.format, LogFormat::kRos1Bag);
  EXPECT_TRUE(bag.notes.empty());
  EXPECT_EQ(bag.scan_topic, mcap.scan_topic);
  EXPECT_EQ(bag.scan.scans, mcap.scan.scans);
  EXPECT_EQ(bag.scan.angle_increment, mcap.scan.angle_increment);
  EXPECT_EQ(bag.laser_frame, mcap.laser_frame);
  EXPECT_EQ(bag.base_frame, mcap.base_frame);
  EXPECT_EQ(bag.X_RL, mcap.X_RL);
  EXPECT_EQ(bag.mount_source, mcap.mount_source);
  EXPECT_EQ(bag.odometry_source, "/odom (nav_msgs/Odometry)");
  EXPECT_EQ(bag.reference_source, "/ground_truth (geometry_msgs/PoseStamped)");
  EXPECT_EQ(bag.origin_ns, mcap.origin_ns);
  ASSERT_EQ(bag.odometry.size(), mcap.odometry.size());
  for (std::size_t i = 0; i < bag.odometry.size(); ++i) {
    EXPECT_EQ(bag.odometry[i].t, mcap.odometry[i].t);
    EXPECT_EQ(bag.odometry[i].pose, mcap.odometry[i].pose);
  }
  ASSERT_EQ(bag.reference.size(), mcap.reference.size());
  EXPECT_EQ(bag.reference.back().pose, mcap.reference.back().pose);
  ASSERT_EQ(bag.topics.size(), mcap.topics.size());
  EXPECT_EQ(bag.topics[2].type, "tf/tfMessage");
  std::vector<core::LaserScan> a, b;
  ReadScans(mcap, 0.0, 1e9, [&](const ScanMessage& m, double) { a.push_back(m.scan); });
  ReadScans(bag, 0.0, 1e9, [&](const ScanMessage& m, double) { b.push_back(m.scan); });
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].stamp, b[i].stamp);
    EXPECT_EQ(a[i].ranges, b[i].ranges);
  }

  // Without its index (a recording cut off) the bag is read all the same, with a note.
  const LogIndex cut = IndexLog(WriteRos1Bag(tmp.path() / "cut.bag", false, false));
  EXPECT_EQ(cut.problem, "");
  ASSERT_FALSE(cut.notes.empty());
  EXPECT_TRUE(cut.notes[0].starts_with("the bag has no index")) << cut.notes[0];
  EXPECT_LT(cut.scan.scans, bag.scan.scans);
}

// A MultiEchoLaserScan feeds the scans (first echo, noted), a PoseWithCovarianceStamped the
// reference; a topic of a single pose (an /initialpose) is no reference, nor a choice to make.
TEST(SensorLog, Ros1MultiEchoScansAndPoseWithCovarianceReference) {
  testing::TempDir tmp;
  const LogIndex index = IndexLog(WriteRos1Bag(tmp.path() / "echo.bag", true));
  EXPECT_EQ(index.problem, "");
  EXPECT_EQ(index.scan_topic, "/scan");
  EXPECT_EQ(index.scan.scans, 51U);
  EXPECT_EQ(index.reference_source, "/amcl_pose (geometry_msgs/PoseWithCovarianceStamped)");
  ExpectNear(index.reference[100].pose, Truth(2.0), 1e-9);
  ASSERT_EQ(index.notes.size(), 2U);
  EXPECT_EQ(index.notes[0],
            "'/initialpose' holds a single pose: not taken as the reference (--reference-topic "
            "takes it)");
  EXPECT_EQ(index.notes[1],
            "'/scan' holds sensor_msgs/MultiEchoLaserScan: the first echo of each beam is its "
            "range (a beam without echoes is no return)");
  std::size_t scans = 0;
  ReadScans(index, 0.0, 1e9, [&](const ScanMessage& m, double) {
    EXPECT_EQ(m.scan.ranges, Scan(m.scan.stamp).ranges);
    ++scans;
  });
  EXPECT_EQ(scans, 51U);
}

// A type of a known name with another md5sum is another definition: refused in one line.
TEST(SensorLog, Ros1TypeWithAnotherMd5sumIsRefusedNamingIt) {
  testing::TempDir tmp;
  testing::Ros1BagBuilder b;
  const auto c0 = testing::Ros1BagBuilder::Connection(0, "/scan", "sensor_msgs/LaserScan",
                                                      "00112233445566778899aabbccddeeff");
  const std::uint64_t pos =
      b.Chunk({c0, testing::Ros1BagBuilder::Message(0, 5, EncodeRos1LaserScan({Scan(0.0), "l"}))});
  b.Index({c0}, {{pos, 5, 5, {{0, 1}}}});
  const fs::path bag = tmp.Write("other.bag", b.Text());
  EXPECT_EQ(testing::IoErrorOf([&] { IndexLog(bag); }),
            bag.string() +
                ": message 1 on '/scan': sensor_msgs/LaserScan: md5sum "
                "'00112233445566778899aabbccddeeff' is not the md5sum of the sensor_msgs/LaserScan "
                "retrace reads (90c7ef2dc6895d81024acba2ac42f369): another definition of the type");
}

// Messages name the types in the bag's ROS.
TEST(SensorLog, Ros1BagWithoutScansIsDescribedInRos1Names) {
  testing::TempDir tmp;
  const fs::path bag = tmp.path() / "odom.bag";
  {
    Ros1BagWriter w(bag, Ros1BagCompression::kNone);
    const std::uint32_t odom = w.AddConnection("/odom", "nav_msgs/Odometry");
    for (int k = 0; k < 3; ++k)
      w.Write(odom, k, EncodeRos1Odometry({1.0 * k, "odom", "base_link", Odometry(k)}));
    w.Close();
  }
  const LogIndex index = IndexLog(bag);
  ASSERT_EQ(index.topics.size(), 1U);
  EXPECT_EQ(index.topics[0].type, "nav_msgs/Odometry");
  EXPECT_EQ(index.topics[0].messages, 3U);
  EXPECT_EQ(index.problem,
            bag.string() +
                ": no sensor_msgs/LaserScan or MultiEchoLaserScan topic: nothing to map or "
                "localize with");
}

TEST(SensorLog, PoseAtInterpolatesInsideAndRefusesOutside) {
  const std::vector<StampedPose> poses = {{1.0, core::Pose2(0, 0, 0)},
                                          {2.0, core::Pose2(2, 0, 1.0)}};
  EXPECT_FALSE(PoseAt(poses, 0.999).has_value());
  EXPECT_FALSE(PoseAt(poses, 2.001).has_value());
  ExpectNear(*PoseAt(poses, 1.0), poses[0].pose, 0.0);
  ExpectNear(*PoseAt(poses, 2.0), poses[1].pose, 0.0);
  ExpectNear(*PoseAt(poses, 1.25), core::Pose2(0.5, 0, 0.25), 1e-12);
  EXPECT_FALSE(PoseAt({}, 1.0).has_value());
  EXPECT_DOUBLE_EQ(PathLength(poses), 2.0);
}

}  // namespace sensor_log_test
}  // namespace retrace::logs
