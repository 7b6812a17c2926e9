#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "logs/carmen_reader.hpp"
#include "logs/carmen_writer.hpp"
#include "tests/support/io_error_of.hpp"
#include "tests/support/special_values.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::logs {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace carmen_test {

namespace fs = std::filesystem;
using retrace::testing::kInf;
using retrace::testing::kNaN;

std::string Text(const RawMessage& m) {
  return std::string(reinterpret_cast<const char*>(m.data.data()), m.data.size());
}

// Every message of a CARMEN log: its type, text, log time and line.
struct Line {
  std::string type;
  std::string text;
  std::int64_t log_time_ns = 0;
  std::size_t line = 0;
};

std::vector<Line> ReadAll(const fs::path& file) {
  CarmenReader reader(file);
  std::vector<Line> lines;
  RawMessage m;
  while (reader.Next(m)) {
    EXPECT_EQ(m.topic, m.type);
    EXPECT_EQ(m.encoding, "carmen");
    lines.push_back({std::string(m.type), Text(m), m.log_time_ns, reader.line()});
  }
  EXPECT_FALSE(reader.Next(m));  // and stays at the end
  return lines;
}

using testing::IoErrorOf;

// A line of `n` ranges in CARMEN's old FLASER format.
std::string Flaser(std::size_t n, double range = 1.5) {
  // Appended piece by piece: GCC 12 at -O3 misreads `"..." + std::string` as an overlap.
  std::string line = "FLASER ";
  line.append(std::to_string(n));
  for (std::size_t i = 0; i < n; ++i) line.append(" ").append(std::to_string(range));
  line.append(" 1.5 -0.25 0.1 1.4 -0.25 0.1 1083.441826 nohost 12.057663");
  return line;
}

// ---------------------------------------------------------------------------------------------
// Round trip through CarmenWriter and CarmenReader, plain and gzipped.

class CarmenRoundTrip : public ::testing::TestWithParam<const char*> {
 protected:
  fs::path File() const { return tmp_.path() / GetParam(); }
  retrace::testing::TempDir tmp_;
};

core::LaserScan TestScan() {
  core::LaserScan scan;
  scan.stamp = 1700000000.123456;
  scan.angle_min = -2.0943951023931953;  // -120 deg
  scan.angle_increment = 0.006135923151542565;
  scan.range_min = 0.05;
  scan.range_max = 30.0;
  for (int i = 0; i < 683; ++i) scan.ranges.push_back(0.5f + 0.0137f * static_cast<float>(i));
  scan.ranges[3] = static_cast<float>(kInf);   // no return
  scan.ranges[4] = static_cast<float>(-kInf);  // too close
  scan.ranges[5] = static_cast<float>(kNaN);   // failed
  scan.ranges[6] = 31.0f;                      // beyond range_max
  scan.ranges[7] = 29.9996f;                   // just below range_max: must stay valid
  scan.ranges[8] = 0.01f;                      // below range_min
  return scan;
}

// The written file's first bytes: gzip's magic, or CARMEN's header comments.
void ExpectHeader(const fs::path& file, const std::string& bytes) {
  if (file.extension() == ".gz") {
    ASSERT_GE(bytes.size(), 2U);
    EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f);  // gzip magic
    EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8b);
  } else {
    EXPECT_EQ(bytes.rfind("# CARMEN Logfile\n", 0), 0U) << bytes.substr(0, 100);
    EXPECT_NE(bytes.find("# ROBOTLASER1 laser_type start_angle"), std::string::npos);
    EXPECT_NE(bytes.find(" retrace "), std::string::npos);
  }
}

// The ranges read back: bit for bit, the special readings as CARMEN can say them.
void ExpectRanges(const core::LaserScan& back, const core::LaserScan& scan) {
  ASSERT_EQ(back.size(), scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (i >= 3 && i <= 8) continue;
    EXPECT_EQ(back.ranges[i], scan.ranges[i]) << i;  // bit for bit
    EXPECT_TRUE(back.Valid(i)) << i;
  }
  EXPECT_EQ(back.ranges[3], static_cast<float>(kInf));
  EXPECT_TRUE(back.NoReturn(3));
  EXPECT_EQ(back.ranges[4], static_cast<float>(-kInf));
  EXPECT_EQ(back.ranges[5], static_cast<float>(-kInf));
  EXPECT_EQ(back.ranges[6], static_cast<float>(kInf));
  EXPECT_EQ(back.ranges[7], 29.9996f);
  EXPECT_EQ(back.ranges[8], 0.01f);  // kept: CARMEN has no range_min, the reader's robot applies it
  for (std::size_t i = 3; i <= 8; ++i) EXPECT_FALSE(std::isnan(back.ranges[i])) << i;
}

// The laser line read back with the PARAM lines before it: its scan and its two poses.
void ExpectLaser(const std::vector<Line>& lines, const core::LaserScan& scan,
                 const core::Pose2& X_OR, const core::Pose2& X_RL) {
  CarmenLaserDefaults defaults;
  for (std::size_t i = 1; i <= 7; ++i) {
    const auto [name, value] = ParseCarmenParam(lines[i].text);
    ApplyCarmenParam(name, value, defaults);
  }
  EXPECT_DOUBLE_EQ(defaults.front.max_range, 30.0);
  ASSERT_TRUE(defaults.front.resolution_deg.has_value());
  EXPECT_DOUBLE_EQ(*defaults.front.resolution_deg, core::RadToDeg(scan.angle_increment));
  EXPECT_DOUBLE_EQ(defaults.front.fov_deg, core::RadToDeg(682 * scan.angle_increment));

  const CarmenLaser laser = ParseCarmenLaser(lines[8].text, defaults);
  EXPECT_EQ(laser.scan.frame_id, "front_laser");
  const core::LaserScan& back = laser.scan.scan;
  EXPECT_EQ(back.angle_min, scan.angle_min);  // exact
  EXPECT_EQ(back.angle_increment, scan.angle_increment);
  EXPECT_EQ(back.range_max, scan.range_max);
  EXPECT_DOUBLE_EQ(back.stamp, scan.stamp);
  ExpectRanges(back, scan);

  ASSERT_TRUE(laser.X_OR.has_value());
  ASSERT_TRUE(laser.X_OL.has_value());
  EXPECT_NEAR(laser.X_OR->x, X_OR.x, 1e-6);
  EXPECT_NEAR(laser.X_OR->y, X_OR.y, 1e-6);
  EXPECT_NEAR(laser.X_OR->theta, X_OR.theta, 1e-6);
  const core::Pose2 X_OL = X_OR * X_RL;
  EXPECT_NEAR(laser.X_OL->x, X_OL.x, 1e-6);
  EXPECT_NEAR(laser.X_OL->y, X_OL.y, 1e-6);
  EXPECT_NEAR(core::AngleDiff(laser.X_OL->theta, X_OL.theta), 0.0, 1e-6);
}

TEST_P(CarmenRoundTrip, KeepsPosesRangesAnglesAndNoReturns) {
  const core::LaserScan scan = TestScan();
  const core::Pose2 X_RL(0.2, -0.015, 0.01);
  const core::Pose2 X_OR(12.3456789012, -4.987654321, 3.0);
  const core::Pose2 X_WR(-101.25, 7.0000001, -3.1);
  {
    CarmenWriter writer(File());
    writer.WriteOdometry(1700000000.1, X_OR, 0.5, -0.25);
    writer.WriteLaser(scan, X_OR, X_RL, 0.5, -0.25);
    writer.WriteTruePose(1700000000.2, X_WR, X_OR);
    writer.Close();
  }
  ExpectHeader(File(), tmp_.Read(File()));

  const std::vector<Line> lines = ReadAll(File());
  ASSERT_EQ(lines.size(), 10U);  // 7 PARAMs before the first laser line, ODOM, laser, TRUEPOS
  EXPECT_EQ(lines[0].type, "ODOM");
  for (std::size_t i = 1; i <= 7; ++i) EXPECT_EQ(lines[i].type, "PARAM") << i;
  EXPECT_EQ(lines[8].type, "ROBOTLASER1");
  EXPECT_EQ(lines[9].type, "TRUEPOS");
  EXPECT_EQ(lines[0].log_time_ns, 1700000000100000000);
  EXPECT_EQ(lines[8].log_time_ns, 1700000000123456000);
  EXPECT_EQ(lines[9].log_time_ns, 1700000000200000000);

  const OdometryMessage odom = ParseCarmenOdometry(lines[0].text);
  EXPECT_EQ(odom.frame_id, "odom");
  EXPECT_EQ(odom.child_frame_id, "base_link");
  EXPECT_NEAR(odom.pose.x, X_OR.x, 1e-6);
  EXPECT_NEAR(odom.pose.y, X_OR.y, 1e-6);
  EXPECT_NEAR(odom.pose.theta, X_OR.theta, 1e-6);
  EXPECT_DOUBLE_EQ(odom.stamp, 1700000000.1);

  ExpectLaser(lines, scan, X_OR, X_RL);

  const PoseStampedMessage truth = ParseCarmenTruePose(lines[9].text);
  EXPECT_EQ(truth.frame_id, "world");
  EXPECT_NEAR(truth.pose.x, X_WR.x, 1e-6);
  EXPECT_NEAR(truth.pose.y, X_WR.y, 1e-6);
  EXPECT_NEAR(truth.pose.theta, X_WR.theta, 1e-6);
  EXPECT_DOUBLE_EQ(truth.stamp, 1700000000.2);
}

TEST_P(CarmenRoundTrip, WritesExplicitParamsOnceAndInOrder) {
  core::LaserScan scan;
  scan.angle_min = -core::kPi / 2.0;
  scan.angle_increment = core::kPi / 180.0;
  scan.range_max = 80.0;
  scan.ranges.assign(181, 2.0f);
  {
    CarmenWriter writer(File());
    writer.WriteParam("robot_name", "retrace_bot");
    writer.WriteLaserParams(scan, core::Pose2(0.1, 0.0, 0.0));
    writer.WriteLaser(scan, core::Pose2(), core::Pose2(0.1, 0.0, 0.0), 0.0, 0.0);
    writer.WriteLaser(scan, core::Pose2(), core::Pose2(0.1, 0.0, 0.0), 0.0, 0.0);
    writer.Close();
    writer.Close();  // a second Close() does nothing
  }
  const std::vector<Line> lines = ReadAll(File());
  ASSERT_EQ(lines.size(), 10U);
  EXPECT_EQ(ParseCarmenParam(lines[0].text),
            (std::pair<std::string, std::string>{"robot_name", "retrace_bot"}));
  CarmenLaserDefaults defaults;
  for (std::size_t i = 1; i <= 7; ++i) {
    ASSERT_EQ(lines[i].type, "PARAM");
    const auto [name, value] = ParseCarmenParam(lines[i].text);
    ApplyCarmenParam(name, value, defaults);
  }
  EXPECT_DOUBLE_EQ(defaults.front.fov_deg, 180.0);
  EXPECT_DOUBLE_EQ(*defaults.front.resolution_deg, 1.0);
  EXPECT_FALSE(defaults.front.flipped);
  EXPECT_EQ(lines[8].type, "ROBOTLASER1");
  EXPECT_EQ(lines[9].type, "ROBOTLASER1");
}

std::string StorageName(const ::testing::TestParamInfo<const char*>& param) {
  return std::string(param.param) == "run.log" ? "Plain" : "Gzip";
}

INSTANTIATE_TEST_SUITE_P(PlainAndGzip, CarmenRoundTrip, ::testing::Values("run.log", "run.log.gz"),
                         StorageName);

using CarmenWriterTest = retrace::testing::TempDirTest;

TEST_F(CarmenWriterTest, RefusesWhatWouldNotReadBack) {
  CarmenWriter writer(tmp_.path() / "a.log");
  EXPECT_NE(IoErrorOf([&] { writer.WriteOdometry(kNaN, core::Pose2(), 0, 0); }).find("non-finite"),
            std::string::npos);
  core::Pose2 bad;
  bad.x = kInf;
  EXPECT_NE(IoErrorOf([&] { writer.WriteTruePose(1.0, bad, core::Pose2()); }).find("non-finite"),
            std::string::npos);
  EXPECT_NE(IoErrorOf([&] { writer.WriteParam("a name", "1"); }).find("one word"),
            std::string::npos);
  EXPECT_NE(IoErrorOf([&] { writer.WriteParam("name", ""); }).find("one word"), std::string::npos);
  core::LaserScan scan;
  scan.range_max = kInf;
  EXPECT_NE(IoErrorOf([&] {
              writer.WriteLaser(scan, core::Pose2(), core::Pose2(), 0, 0);
            }).find("range_max"),
            std::string::npos);
  writer.Close();
  EXPECT_NE(IoErrorOf([&] { writer.WriteOdometry(1.0, core::Pose2(), 0, 0); }).find("closed"),
            std::string::npos);
}

TEST_F(CarmenWriterTest, ReportsFilesItCannotCreateOrWrite) {
  const std::string missing_folder =
      IoErrorOf([&] { CarmenWriter writer(tmp_.path() / "no_such_folder" / "a.log"); });
  EXPECT_NE(missing_folder.find("cannot create file"), std::string::npos) << missing_folder;
  EXPECT_NE(missing_folder.find("a.log"), std::string::npos) << missing_folder;
  ASSERT_TRUE(fs::exists("/dev/full")) << "Linux has /dev/full: a device that is always full";
  const std::string full = IoErrorOf([] {
    CarmenWriter writer("/dev/full");
    for (int i = 0; i < 1000; ++i) writer.WriteOdometry(i, core::Pose2(i, i, 0.0), 0, 0);
    writer.Close();
  });
  EXPECT_NE(full.find("/dev/full: cannot write"), std::string::npos) << full;
}

// ---------------------------------------------------------------------------------------------
// Lines in the style of real logs.

TEST(CarmenParse, FlaserFollowsCarmensGuessedGeometry) {
  // 180 readings: 1 deg steps from -90 deg, the last beam at +89 deg (CARMEN's readlog.c).
  const CarmenLaser l180 = ParseCarmenLaser(Flaser(180));
  EXPECT_EQ(l180.scan.frame_id, "front_laser");
  EXPECT_EQ(l180.scan.scan.angle_min, -core::kPi / 2.0);
  EXPECT_EQ(l180.scan.scan.angle_increment, core::kPi / 180.0);
  EXPECT_NEAR(l180.scan.scan.Angle(179), core::DegToRad(89.0), 1e-12);
  EXPECT_EQ(l180.scan.scan.range_max, 80.0);
  // 181: 1 deg steps, -90 deg to +90 deg.
  const CarmenLaser l181 = ParseCarmenLaser(Flaser(181));
  EXPECT_EQ(l181.scan.scan.angle_increment, core::kPi / 180.0);
  EXPECT_NEAR(l181.scan.scan.Angle(180), core::kPi / 2.0, 1e-12);
  // 360 and 361: 0.5 deg; 400 and 401: 0.25 deg.
  EXPECT_EQ(ParseCarmenLaser(Flaser(360)).scan.scan.angle_increment, core::kPi / 360.0);
  EXPECT_EQ(ParseCarmenLaser(Flaser(361)).scan.scan.angle_increment, core::kPi / 360.0);
  EXPECT_EQ(ParseCarmenLaser(Flaser(401)).scan.scan.angle_increment, core::kPi / 720.0);
  // Any other count spans 180 deg with the first and last beam at -90 and +90 deg.
  const CarmenLaser l541 = ParseCarmenLaser(Flaser(541));
  EXPECT_EQ(l541.scan.scan.angle_increment, core::kPi / 540.0);
  EXPECT_NEAR(l541.scan.scan.Angle(540), core::kPi / 2.0, 1e-12);
}

TEST(CarmenParse, FlaserReadsRangesPosesAndStamp) {
  const std::string line =
      "FLASER 6 1.09 0.99 81.83 80.00 79.99 0 0.600266 -0.0320327 -0.354665 0.5 -0.03 -0.35 "
      "1083.441826 hostname 12.057663";
  const CarmenLaser laser = ParseCarmenLaser(line);
  const core::LaserScan& s = laser.scan.scan;
  ASSERT_EQ(s.size(), 6U);
  EXPECT_FLOAT_EQ(s.ranges[0], 1.09f);
  EXPECT_FLOAT_EQ(s.ranges[1], 0.99f);
  EXPECT_EQ(s.ranges[2], static_cast<float>(kInf));  // the Intel log's 81.83: no return
  EXPECT_EQ(s.ranges[3], static_cast<float>(kInf));  // at the maximum range
  EXPECT_FLOAT_EQ(s.ranges[4], 79.99f);
  EXPECT_EQ(s.ranges[5], static_cast<float>(-kInf));  // failed reading
  EXPECT_TRUE(s.NoReturn(2));
  EXPECT_FALSE(s.Valid(5));
  EXPECT_DOUBLE_EQ(s.stamp, 1083.441826);
  ASSERT_TRUE(laser.X_OL && laser.X_OR);
  EXPECT_DOUBLE_EQ(laser.X_OL->x, 0.600266);
  EXPECT_DOUBLE_EQ(laser.X_OL->y, -0.0320327);
  EXPECT_DOUBLE_EQ(laser.X_OL->theta, -0.354665);
  EXPECT_DOUBLE_EQ(laser.X_OR->x, 0.5);
  EXPECT_DOUBLE_EQ(laser.X_OR->theta, -0.35);
}

TEST(CarmenParse, ParamsOverrideTheOldLaserGeometry) {
  CarmenLaserDefaults d;
  EXPECT_TRUE(ApplyCarmenParam("laser_front_laser_fov", "100", d));
  EXPECT_TRUE(ApplyCarmenParam("laser_front_laser_resolution", "0.25", d));
  EXPECT_TRUE(ApplyCarmenParam("robot_front_laser_max", "49.9", d));
  EXPECT_TRUE(ApplyCarmenParam("laser_front_laser_flipped", "1", d));
  EXPECT_TRUE(ApplyCarmenParam("laser_rear_laser_fov", "270", d));
  EXPECT_TRUE(ApplyCarmenParam("robot_rear_laser_max", "30", d));
  EXPECT_FALSE(ApplyCarmenParam("robot_frontlaser_offset", "0.2", d));
  EXPECT_FALSE(ApplyCarmenParam("laser_front_laser_dev", "/dev/ttyS0", d));
  EXPECT_TRUE(d.front.flipped);
  const CarmenLaser front = ParseCarmenLaser(Flaser(401, 49.95), d);
  EXPECT_EQ(front.scan.scan.angle_min, -core::DegToRad(100.0) / 2.0);
  EXPECT_EQ(front.scan.scan.angle_increment, core::DegToRad(0.25));
  EXPECT_EQ(front.scan.scan.range_max, 49.9);
  EXPECT_EQ(front.scan.scan.ranges[0], static_cast<float>(kInf));
  // The ranges are not reversed for a flipped laser: CARMEN's laser module already did it.
  std::string rline = Flaser(3);
  rline.replace(0, 6, "RLASER");
  const CarmenLaser rear = ParseCarmenLaser(rline, d);
  EXPECT_EQ(rear.scan.frame_id, "rear_laser");
  EXPECT_EQ(rear.scan.scan.angle_min, -core::DegToRad(135.0));
  EXPECT_EQ(rear.scan.scan.angle_increment, core::DegToRad(135.0));  // fov / (n - 1)
  EXPECT_EQ(rear.scan.scan.range_max, 30.0);

  const std::string bad_fov = IoErrorOf([&] { ApplyCarmenParam("laser_front_laser_fov", "0", d); });
  EXPECT_NE(bad_fov.find("laser_front_laser_fov"), std::string::npos) << bad_fov;
  EXPECT_NE(IoErrorOf([&] { ApplyCarmenParam("robot_front_laser_max", "nan", d); }), "");
  EXPECT_NE(IoErrorOf([&] { ApplyCarmenParam("robot_front_laser_max", "-1", d); }), "");
}

// laser_*_laser_flipped is information only: read as a boolean however it is spelled, and never
// a reason to refuse a log when it is not one.
TEST(CarmenParse, FlippedIsABooleanOfAnySpellingAndNeverAnError) {
  CarmenLaserDefaults d;
  for (const char* yes : {"1", "on", "yes", "true", "Yes", "TRUE"}) {
    d.front.flipped = false;
    EXPECT_TRUE(ApplyCarmenParam("laser_front_laser_flipped", yes, d));
    EXPECT_TRUE(d.front.flipped) << yes;
  }
  for (const char* no : {"0", "off", "no", "false", "No", "OFF"}) {
    d.front.flipped = true;
    EXPECT_TRUE(ApplyCarmenParam("laser_front_laser_flipped", no, d));
    EXPECT_FALSE(d.front.flipped) << no;
  }
  EXPECT_EQ(IoErrorOf([&] { ApplyCarmenParam("laser_front_laser_flipped", "upside down", d); }),
            "");
  EXPECT_FALSE(d.front.flipped);  // unchanged
}

// A PARAM line retrace does not read is skipped whatever it holds; one it reads is applied, and
// refused when malformed.
TEST(CarmenParse, ParamLinesRetraceDoesNotReadAreSkipped) {
  CarmenLaserDefaults d;
  EXPECT_TRUE(ApplyCarmenParamLine("PARAM laser_front_laser_flipped no nohost 0", d));
  EXPECT_FALSE(d.front.flipped);
  EXPECT_TRUE(ApplyCarmenParamLine("PARAM laser_rear_laser_flipped on 12.5 host 0.3", d));
  EXPECT_TRUE(d.rear.flipped);
  for (const char* line :
       {"PARAM robot_allow_rear_motion yes nohost 0", "PARAM robot_name the blue pioneer nohost 0",
        "PARAM lonely", "PARAM", "PARAM laser_front_laser_dev /dev/ttyS0 12.5 host 0.3"}) {
    EXPECT_EQ(IoErrorOf([&] { EXPECT_FALSE(ApplyCarmenParamLine(line, d)) << line; }), "") << line;
  }
  EXPECT_TRUE(ApplyCarmenParamLine("PARAM robot_front_laser_max 49.9 nohost 0", d));
  EXPECT_EQ(d.front.max_range, 49.9);
  EXPECT_EQ(IoErrorOf([&] { ApplyCarmenParamLine("PARAM robot_front_laser_max far nohost 0", d); }),
            "PARAM robot_front_laser_max: 'far' is not a finite number");
  EXPECT_EQ(IoErrorOf([&] { ApplyCarmenParamLine("PARAM laser_front_laser_fov", d); }),
            "PARAM laser_front_laser_fov: no value");
  EXPECT_NE(IoErrorOf([&] { ApplyCarmenParamLine("ODOM 0 0 0 0 0 0 1 h 1", d); }).find("PARAM"),
            std::string::npos);
}

TEST(CarmenParse, ParamLinesOfEveryVintage) {
  using P = std::pair<std::string, std::string>;
  EXPECT_EQ(ParseCarmenParam("PARAM robot_front_laser_max 49.9 1083.400000 robot1 0.000251"),
            (P{"robot_front_laser_max", "49.9"}));
  // Old logs: `PARAM name value hostname timestamp`.
  EXPECT_EQ(ParseCarmenParam("PARAM robot_frontlaser_offset 0.0 nohost 0"),
            (P{"robot_frontlaser_offset", "0.0"}));
  EXPECT_EQ(ParseCarmenParam("PARAM laser_front_laser_dev /dev/ttyS0"),
            (P{"laser_front_laser_dev", "/dev/ttyS0"}));
  EXPECT_EQ(ParseCarmenParam("PARAM robot_allow_rear_motion on 12.5 host 0.3"),
            (P{"robot_allow_rear_motion", "on"}));
  EXPECT_NE(IoErrorOf([] { ParseCarmenParam("PARAM lonely"); }).find("name and a value"),
            std::string::npos);
  EXPECT_NE(IoErrorOf([] { ParseCarmenParam("ODOM 0 0 0 0 0 0 1 h 1"); }).find("PARAM"),
            std::string::npos);
}

TEST(CarmenParse, OdometryAndTruePose) {
  const OdometryMessage odom = ParseCarmenOdometry(
      "ODOM 7.184211 -1.250045 2.911590 0.250000 -0.050000 0.000000 "
      "1083.441826 robot1 12.057663");
  EXPECT_DOUBLE_EQ(odom.pose.x, 7.184211);
  EXPECT_DOUBLE_EQ(odom.pose.y, -1.250045);
  EXPECT_DOUBLE_EQ(odom.pose.theta, 2.911590);
  EXPECT_DOUBLE_EQ(odom.stamp, 1083.441826);
  // Headings are wrapped into [-pi, pi).
  EXPECT_NEAR(ParseCarmenOdometry("ODOM 0 0 4.0 0 0 0 1 h 1").pose.theta, 4.0 - 2.0 * core::kPi,
              1e-12);
  const PoseStampedMessage truth = ParseCarmenTruePose(
      "TRUEPOS 20.100000 5.200000 1.570796 7.184211 -1.250045 2.911590 1083.44 sim 12.06");
  EXPECT_EQ(truth.frame_id, "world");
  EXPECT_DOUBLE_EQ(truth.pose.x, 20.1);
  EXPECT_DOUBLE_EQ(truth.pose.y, 5.2);
  EXPECT_DOUBLE_EQ(truth.pose.theta, 1.570796);
  EXPECT_DOUBLE_EQ(truth.stamp, 1083.44);
}

TEST(CarmenParse, RobotLaserAndRawLaserCarryTheirGeometry) {
  const std::string robotlaser =
      "ROBOTLASER1 0 -1.570796 3.141593 0.017453 81.900000 0.010000 0 5 1.00 2.00 3.00 81.90 "
      "4.00 2 0.5 0.6 10.0 20.0 0.5 9.9 20.0 0.5 0.3 0.1 0.0 0.0 1000000.0 1083.44 robot1 12.06";
  const CarmenLaser laser = ParseCarmenLaser(robotlaser);
  EXPECT_EQ(laser.scan.frame_id, "front_laser");
  const core::LaserScan& s = laser.scan.scan;
  EXPECT_EQ(s.angle_min, -1.570796);
  EXPECT_EQ(s.angle_increment, 0.017453);
  EXPECT_EQ(s.range_max, 81.9);
  ASSERT_EQ(s.size(), 5U);
  EXPECT_FLOAT_EQ(s.ranges[2], 3.0f);
  EXPECT_EQ(s.ranges[3], static_cast<float>(kInf));
  ASSERT_TRUE(laser.X_OL && laser.X_OR);
  EXPECT_DOUBLE_EQ(laser.X_OL->x, 10.0);
  EXPECT_DOUBLE_EQ(laser.X_OR->x, 9.9);
  EXPECT_DOUBLE_EQ(laser.X_OR->theta, 0.5);
  EXPECT_DOUBLE_EQ(s.stamp, 1083.44);

  const CarmenLaser raw = ParseCarmenLaser(
      "RAWLASER3 4 -2.356194 4.712389 0.008727 30.0 0.01 0 3 1.0 2.0 3.0 0 1083.44 host 12.06");
  EXPECT_EQ(raw.scan.frame_id, "laser3");
  EXPECT_FALSE(raw.X_OL.has_value());
  EXPECT_FALSE(raw.X_OR.has_value());
  EXPECT_EQ(raw.scan.scan.angle_min, -2.356194);
  EXPECT_EQ(raw.scan.scan.size(), 3U);
  EXPECT_TRUE(IsCarmenLaser("RAWLASER4"));
  EXPECT_FALSE(IsCarmenLaser("ODOM"));
}

TEST(CarmenParse, BadLinesThrowShortClearErrors) {
  const auto error = [](std::string_view line) {
    return IoErrorOf([&] { ParseCarmenLaser(line); });
  };
  // A count beyond the line's fields, and one that would allocate terabytes.
  EXPECT_NE(error("FLASER 200 1 2 3 0 0 0 0 0 0 1 h 1").find("num_readings 200 is larger than"),
            std::string::npos)
      << error("FLASER 200 1 2 3 0 0 0 0 0 0 1 h 1");
  EXPECT_NE(error("FLASER 99999999999 1 2 3").find("num_readings 99999999999 is larger"),
            std::string::npos);
  EXPECT_NE(error("FLASER 999999999999999999999999 1 2").find("larger than"), std::string::npos);
  EXPECT_NE(error("FLASER -3 1 2 3").find("not a non-negative integer"), std::string::npos);
  EXPECT_NE(error("FLASER 3.5 1 2 3").find("not a non-negative integer"), std::string::npos);
  // Fields left over, or missing.
  EXPECT_NE(error("FLASER 2 1 2 0 0 0 0 0 0 1 h 1 extra").find("expected 13 fields"),
            std::string::npos);
  EXPECT_NE(error("FLASER 2 1 2 0 0 0 0 0 0 1 h").find("expected 13 fields"), std::string::npos);
  // Non-numeric, NaN and infinite values.
  EXPECT_NE(error("FLASER 2 1 abc 0 0 0 0 0 0 1 h 1").find("range 1 'abc' is not a number"),
            std::string::npos);
  EXPECT_NE(error("FLASER 2 1 2 nan 0 0 0 0 0 1 h 1").find("laser pose x 'nan' is not finite"),
            std::string::npos);
  EXPECT_NE(error("FLASER 2 1 2 0 0 0 0 inf 0 1 h 1").find("robot pose y 'inf' is not finite"),
            std::string::npos);
  EXPECT_NE(error("FLASER 2 1 2 0 0 0 0 0 0 x h 1").find("ipc_timestamp"), std::string::npos);
  EXPECT_NE(error("FLASER 2 1 inf 0 0 0 0 0 0 1 h 1").find("range 1 'inf' is not finite"),
            std::string::npos);
  EXPECT_NE(error("ROBOTLASER1 0 -1.57 3.14 0.0174 0 0.01 0 1 1.0 0 0 0 0 0 0 0 0 0 0 0 0 1 h 1")
                .find("maximum_range '0' is not positive"),
            std::string::npos);
  EXPECT_NE(
      error("ROBOTLASER1 0 -1.57 3.14 0.0174 80 0.01 0 1 1.0 99999999999 0 0 0 0 0 0 0 0 0 0 0 "
            "1 h 1")
          .find("num_remissions 99999999999 is larger"),
      std::string::npos);
  EXPECT_NE(error("ODOM 1 2 3 4 5 6 1 h 1").find("not a CARMEN laser line"), std::string::npos);
  EXPECT_NE(error("").find("not a CARMEN laser line"), std::string::npos);

  EXPECT_NE(IoErrorOf([] { ParseCarmenOdometry("ODOM 1 2 3"); }).find("expected 10 fields"),
            std::string::npos);
  EXPECT_NE(IoErrorOf([] {
              ParseCarmenOdometry("ODOM 1 2 NaN 0 0 0 1 h 1");
            }).find("pose theta 'NaN' is not finite"),
            std::string::npos);
  EXPECT_NE(IoErrorOf([] {
              ParseCarmenOdometry("FLASER 0 0 0 0 0 0 0 1 h 1");
            }).find("ODOM line expected"),
            std::string::npos);
  EXPECT_NE(IoErrorOf([] {
              ParseCarmenTruePose("TRUEPOS 1 2 3 4 5 six 1 h 1");
            }).find("odometry pose theta 'six' is not a number"),
            std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// CarmenReader

using CarmenReaderTest = retrace::testing::TempDirTest;

TEST_F(CarmenReaderTest, SkipsCommentsAndBlankLinesAndKeepsLineNumbers) {
  const fs::path file = tmp_.Write("a.clf",
                                   "# CARMEN Logfile\r\n"
                                   "\r\n"
                                   "PARAM robot_frontlaser_offset 0.0 nohost 0\r\n"
                                   "   # indented comment\n"
                                   "\t\n"
                                   "ODOM 0 0 0 0 0 0 1083.441826 robot1 12.057663\r\n"
                                   "NEFF 15\n"
                                   "SYNC tag 1700000000.5 host 1700000000.000000001\n"
                                   "UNKNOWN_MESSAGE a b c\n"
                                   "ODOM 1 0 0 0 0 0 1e3 robot1 1.5e1");  // no final line break
  const std::vector<Line> lines = ReadAll(file);
  ASSERT_EQ(lines.size(), 6U);
  EXPECT_EQ(lines[0].type, "PARAM");
  EXPECT_EQ(lines[0].line, 3U);
  EXPECT_EQ(lines[0].text, "PARAM robot_frontlaser_offset 0.0 nohost 0");  // no '\r'
  EXPECT_EQ(lines[0].log_time_ns, 0);
  EXPECT_EQ(lines[1].type, "ODOM");
  EXPECT_EQ(lines[1].line, 6U);
  EXPECT_EQ(lines[1].log_time_ns, 12'057'663'000);
  EXPECT_EQ(lines[2].type, "NEFF");  // too short to end in a timestamp
  EXPECT_EQ(lines[2].log_time_ns, 0);
  EXPECT_EQ(lines[3].type, "SYNC");
  EXPECT_EQ(lines[3].log_time_ns, 1'700'000'000'000'000'001);  // exact to the nanosecond
  EXPECT_EQ(lines[4].type, "UNKNOWN_MESSAGE");
  EXPECT_EQ(lines[4].log_time_ns, 0);
  EXPECT_EQ(lines[5].line, 10U);
  EXPECT_EQ(lines[5].text, "ODOM 1 0 0 0 0 0 1e3 robot1 1.5e1");
  EXPECT_EQ(lines[5].log_time_ns, 15'000'000'000);
}

TEST_F(CarmenReaderTest, LocationNamesFileAndLine) {
  const fs::path file = tmp_.Write("b.log", "# c\nODOM 1 2 3 4 5 6 1 h 1\nODOM x\n");
  CarmenReader reader(file);
  RawMessage m;
  ASSERT_TRUE(reader.Next(m));
  ASSERT_TRUE(reader.Next(m));
  EXPECT_EQ(reader.Location(), file.string() + ":3");
  EXPECT_EQ(reader.name(), file.string());
}

TEST_F(CarmenReaderTest, RefusesEmptyMissingAndFolderInputs) {
  const std::string empty = IoErrorOf([&] { CarmenReader r(tmp_.Write("empty.log", "")); });
  EXPECT_NE(empty.find("no CARMEN messages"), std::string::npos) << empty;
  EXPECT_NE(empty.find("empty.log"), std::string::npos) << empty;
  const std::string comments =
      IoErrorOf([&] { CarmenReader r(tmp_.Write("comments.log", "# only\n\n# comments\n")); });
  EXPECT_NE(comments.find("no CARMEN messages"), std::string::npos) << comments;
  const std::string missing = IoErrorOf([&] { CarmenReader r(tmp_.path() / "missing.log"); });
  EXPECT_NE(missing.find("cannot open file"), std::string::npos) << missing;
  const std::string folder = IoErrorOf([&] { CarmenReader r(tmp_.path()); });
  EXPECT_NE(folder.find("folder"), std::string::npos) << folder;
}

TEST_F(CarmenReaderTest, StopsAtAHugeLineWithoutNewline) {
  std::string bytes = "ODOM 0 0 0 0 0 0 1 h 1\n";
  bytes += std::string(10 << 20, 'x');  // 10 MB, no line break
  const fs::path file = tmp_.Write("huge.log", bytes);
  CarmenReader reader(file);
  RawMessage m;
  ASSERT_TRUE(reader.Next(m));
  const std::string error = IoErrorOf([&] { reader.Next(m); });
  EXPECT_NE(error.find("huge.log: line 2 is longer than 1 MiB"), std::string::npos) << error;
}

TEST_F(CarmenReaderTest, ReportsATruncatedGzipFile) {
  const fs::path file = tmp_.path() / "long.log.gz";
  {
    CarmenWriter writer(file);
    for (int i = 0; i < 5000; ++i) {
      writer.WriteOdometry(1000.0 + 0.01 * i, core::Pose2(0.001 * i * i, std::sin(i), 0.1 * i), 0.3,
                           0.01 * i);
    }
    writer.Close();
  }
  const std::string bytes = tmp_.Read(file);
  ASSERT_GT(bytes.size(), 10000U);
  const fs::path cut = tmp_.Write("cut.log.gz", bytes.substr(0, bytes.size() / 2));
  std::size_t read = 0;
  const std::string error = IoErrorOf([&] {
    CarmenReader reader(cut);
    RawMessage m;
    while (reader.Next(m)) ++read;
  });
  EXPECT_NE(error.find("cut.log.gz: truncated gzip file"), std::string::npos) << error;
  EXPECT_GT(read, 0U);
  EXPECT_LT(read, 5000U);

  // The whole file reads back completely.
  std::size_t all = 0;
  CarmenReader reader(file);
  RawMessage m;
  while (reader.Next(m)) {
    ParseCarmenOdometry(Text(m));
    ++all;
  }
  EXPECT_EQ(all, 5000U);
}

TEST_F(CarmenReaderTest, ReportsCorruptGzipData) {
  const fs::path file = tmp_.path() / "c.log.gz";
  {
    CarmenWriter writer(file);
    for (int i = 0; i < 2000; ++i) writer.WriteOdometry(i, core::Pose2(i, -i, 0.0), 0, 0);
    writer.Close();
  }
  std::string bytes = tmp_.Read(file);
  for (std::size_t i = bytes.size() / 3; i < bytes.size() / 3 + 64; ++i) bytes[i] ^= 0x5a;
  const fs::path bad = tmp_.Write("bad.log.gz", bytes);
  const std::string error = IoErrorOf([&] {
    CarmenReader reader(bad);
    RawMessage m;
    while (reader.Next(m)) {
    }
  });
  EXPECT_NE(error.find("bad.log.gz: "), std::string::npos) << error;
}

}  // namespace carmen_test
}  // namespace retrace::logs
