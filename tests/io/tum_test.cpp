#include "io/tum.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::io {
namespace {

namespace fs = std::filesystem;

class TumTest : public ::testing::Test {
 protected:
  // The IoError message of ReadTum on `text`, or "" if it did not throw.
  std::string ErrorFor(const std::string& text) const {
    const fs::path p = tmp_.Write("bad.tum", text);
    try {
      ReadTum(p);
    } catch (const core::IoError& e) {
      return e.what();
    }
    return "";
  }

  retrace::testing::TempDir tmp_;
};

TEST_F(TumTest, RoundTripKeepsTimesPositionsAndHeadings) {
  std::vector<StampedPose> poses;
  for (int i = 0; i < 50; ++i) {
    const double theta = -core::kPi + 0.1283 * i;  // covers the whole circle, including -pi
    poses.push_back({0.05 * i + 1e-9, core::Pose2(1.0 / 3.0 * i, -2.0e-7 * i, theta)});
  }
  const fs::path path = tmp_.path() / "runs" / "0" / "gt.tum";
  WriteTum(path, poses);
  const std::vector<StampedPose> back = ReadTum(path);
  ASSERT_EQ(back.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(back[i].t, poses[i].t);
    EXPECT_EQ(back[i].pose.x, poses[i].pose.x);
    EXPECT_EQ(back[i].pose.y, poses[i].pose.y);
    EXPECT_NEAR(core::AngleDiff(back[i].pose.theta, poses[i].pose.theta), 0.0, 1e-14) << i;
  }
}

TEST_F(TumTest, WritesEightColumnsWithPlanarQuaternion) {
  WriteTum(tmp_.path() / "a.tum", {{1.5, core::Pose2(2.0, 3.0, core::kPi / 2.0)}});
  std::ifstream in(tmp_.path() / "a.tum");
  std::string header, line;
  std::getline(in, header);
  std::getline(in, line);
  EXPECT_EQ(header, "# t x y z qx qy qz qw");
  std::istringstream ss(line);
  std::vector<double> v;
  for (double x; ss >> x;) v.push_back(x);
  ASSERT_EQ(v.size(), 8u) << line;
  EXPECT_EQ(v[0], 1.5);
  EXPECT_EQ(v[1], 2.0);
  EXPECT_EQ(v[2], 3.0);
  EXPECT_EQ(v[3], 0.0);
  EXPECT_EQ(v[4], 0.0);
  EXPECT_EQ(v[5], 0.0);
  EXPECT_NEAR(v[6], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(v[7], std::sqrt(0.5), 1e-15);
}

TEST_F(TumTest, ReadsCommentsBlankLinesCrlfAndUnnormalisedQuaternions) {
  const fs::path p = tmp_.Write("in.tum",
                                "# timestamp tx ty tz qx qy qz qw\r\n"
                                "\r\n"
                                "0.0 1 2 0.5 0 0 0 1\r\n"
                                "   \t\n"
                                "1.0\t3 4 0 0 0 2 0   # half turn, quaternion not normalised\n");
  const auto poses = ReadTum(p);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].t, 0.0);
  EXPECT_EQ(poses[0].pose, core::Pose2(1.0, 2.0, 0.0));
  EXPECT_EQ(poses[1].t, 1.0);
  EXPECT_EQ(poses[1].pose.x, 3.0);
  EXPECT_NEAR(std::abs(poses[1].pose.theta), core::kPi, 1e-12);
}

TEST_F(TumTest, ReadsYawOfTiltedQuaternion) {
  // Yaw 0.7 rad combined with a roll: the heading is still the yaw.
  const double yaw = 0.7, roll = 0.2;
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2), cr = std::cos(roll / 2),
               sr = std::sin(roll / 2);
  std::ostringstream line;
  line.precision(17);
  line << "0 0 0 0 " << sr * cy << " " << sr * sy << " " << cr * sy << " " << cr * cy << "\n";
  const auto poses = ReadTum(tmp_.Write("tilt.tum", line.str()));
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_NEAR(poses[0].pose.theta, yaw, 1e-12);
}

// Issue 16: squares of 1e200 overflowed, and the heading read as NaN without a word.
TEST_F(TumTest, HugeQuaternionComponentsGiveTheirHeadingNotNan) {
  const auto poses = ReadTum(tmp_.Write("huge.tum", "0 1 2 0 0 0 1e200 1e200\n"));
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_NEAR(poses[0].pose.theta, core::kPi / 2, 1e-12);
  EXPECT_NE(ErrorFor("0 1 2 0 0 0 1e-300 1e-300\n").find(":1: the quaternion is zero"),
            std::string::npos);
}

TEST_F(TumTest, MalformedLinesNameFileAndLine) {
  const std::string where = (tmp_.path() / "bad.tum").string();
  std::string msg = ErrorFor("0 0 0 0 0 0 0 1\n# comment\n1 0 0 0 0 0 1\n");
  EXPECT_NE(msg.find(where + ":3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected 8 numbers"), std::string::npos) << msg;

  msg = ErrorFor("0 0 0 0 0 0 0 1\n1 0 abc 0 0 0 0 1\n");
  EXPECT_NE(msg.find(where + ":2:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'abc' is not a number"), std::string::npos) << msg;

  msg = ErrorFor("0 nan 0 0 0 0 0 1\n");
  EXPECT_NE(msg.find(where + ":1:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not finite"), std::string::npos) << msg;

  msg = ErrorFor("0 0 0 0 0 0 0 1 9\n");
  EXPECT_NE(msg.find(where + ":1:"), std::string::npos) << msg;

  msg = ErrorFor("0 1 2 0 0 0 0 0\n");
  EXPECT_NE(msg.find(where + ":1:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("quaternion is zero"), std::string::npos) << msg;

  msg = ErrorFor("0,1,2,0,0,0,0,1\n");
  EXPECT_NE(msg.find(where + ":1:"), std::string::npos) << msg;
}

TEST_F(TumTest, EmptyFileGivesEmptyTrajectory) {
  EXPECT_TRUE(ReadTum(tmp_.Write("empty.tum", "# only a comment\n")).empty());
}

TEST_F(TumTest, MissingFileIsIoError) {
  try {
    ReadTum(tmp_.path() / "missing.tum");
    FAIL() << "expected IoError";
  } catch (const core::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.tum"), std::string::npos);
  }
}

}  // namespace
}  // namespace retrace::io
