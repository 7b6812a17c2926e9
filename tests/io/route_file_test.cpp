#include "io/route_file.hpp"

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

class RouteFileTest : public ::testing::Test {
 protected:
  // The IoError message of ReadRouteFile on `text`, or "" if it did not throw.
  std::string RouteErrorFor(const std::string& text) const {
    const fs::path p = tmp_.Write("bad.txt", text);
    try {
      ReadRouteFile(p);
    } catch (const core::IoError& e) {
      return e.what();
    }
    return "";
  }

  retrace::testing::TempDir tmp_;
};

TEST_F(RouteFileTest, ReadsTwoColumnWaypointsWithComments) {
  const auto route = ReadRouteFile(tmp_.Write("route.txt",
                                              "# x y\n"
                                              "0 0\n"
                                              "\n"
                                              "10.5 -2   # corner\r\n"
                                              "\t20 1e1\n"));
  ASSERT_EQ(route.size(), 3u);
  EXPECT_EQ(route[0], core::Vec2(0, 0));
  EXPECT_EQ(route[1], core::Vec2(10.5, -2));
  EXPECT_EQ(route[2], core::Vec2(20, 10));
}

TEST_F(RouteFileTest, ReadsAutoNaviSevenColumnPositions) {
  const auto route = ReadRouteFile(tmp_.Write("path_0.txt",
                                              "0 0 0 0 0 0 1\n"
                                              "0.5 0.1 0 0 0 0.0499792 0.99875\n"));
  ASSERT_EQ(route.size(), 2u);
  EXPECT_EQ(route[1], core::Vec2(0.5, 0.1));
}

TEST_F(RouteFileTest, BadRoutesNameFileAndLine) {
  const std::string where = (tmp_.path() / "bad.txt").string();
  std::string msg = RouteErrorFor("0 0\n1 1\n# c\n2 2 0 0 0 0 1\n");
  EXPECT_NE(msg.find(where + ":4:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected 2 columns as on line 1, got 7"), std::string::npos) << msg;

  msg = RouteErrorFor("0 0\n1 x\n");
  EXPECT_NE(msg.find(where + ":2:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'x' is not a number"), std::string::npos) << msg;

  msg = RouteErrorFor("0 0\nnan 1\n");
  EXPECT_NE(msg.find(where + ":2:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not finite"), std::string::npos) << msg;

  msg = RouteErrorFor("0 0\n1 inf\n");
  EXPECT_NE(msg.find(where + ":2:"), std::string::npos) << msg;

  msg = RouteErrorFor("\n0 0 0\n1 1 1\n");
  EXPECT_NE(msg.find(where + ":2:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected 2 columns (x y) or 7"), std::string::npos) << msg;

  msg = RouteErrorFor("# one point\n3 4\n");
  EXPECT_NE(msg.find(where + ":2: a route needs at least 2 waypoints, got 1"), std::string::npos)
      << msg;

  msg = RouteErrorFor("");
  EXPECT_NE(msg.find("at least 2 waypoints, got 0"), std::string::npos) << msg;
}

TEST_F(RouteFileTest, MissingRouteFileIsIoError) {
  EXPECT_THROW(ReadRouteFile(tmp_.path() / "missing.txt"), core::IoError);
  EXPECT_THROW(ReadRouteFile(tmp_.path()), core::IoError);
}

TEST_F(RouteFileTest, PathFileRoundTrip) {
  std::vector<core::Pose2> poses;
  for (int i = 0; i < 40; ++i) {
    poses.emplace_back(0.1 * i, std::sin(0.3 * i) / 7.0, -core::kPi + 0.16 * i);
  }
  const core::Path path(poses);
  const fs::path file = tmp_.path() / "teach" / "paths" / "path_0.txt";
  WritePathFile(file, path);
  const core::Path back = ReadPathFile(file);
  ASSERT_EQ(back.size(), path.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    EXPECT_EQ(back[i].x, path[i].x);
    EXPECT_EQ(back[i].y, path[i].y);
    EXPECT_NEAR(core::AngleDiff(back[i].theta, path[i].theta), 0.0, 1e-14) << i;
  }
  EXPECT_NEAR(back.Length(), path.Length(), 1e-12);
}

TEST_F(RouteFileTest, PathFileIsSevenColumnsWithZeroZ) {
  WritePathFile(tmp_.path() / "p.txt", core::Path({core::Pose2(1.0, 2.0, core::kPi / 2.0)}));
  std::ifstream in(tmp_.path() / "p.txt");
  std::string line;
  std::getline(in, line);
  std::istringstream ss(line);
  std::vector<double> v;
  for (double x; ss >> x;) v.push_back(x);
  ASSERT_EQ(v.size(), 7u) << line;
  EXPECT_EQ(v[0], 1.0);
  EXPECT_EQ(v[1], 2.0);
  EXPECT_EQ(v[2], 0.0);
  EXPECT_NEAR(v[5], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(v[6], std::sqrt(0.5), 1e-15);
}

// Issue 16: a taught path with such a line played back with heading NaN and exit 0.
TEST_F(RouteFileTest, HugeQuaternionComponentsGiveTheirHeadingNotNan) {
  const core::Path path =
      ReadPathFile(tmp_.Write("huge.txt", "1 2 0 0 0 1e200 1e200\n3 2 0 0 0 1e200 1e200\n"));
  ASSERT_EQ(path.size(), 2u);
  EXPECT_NEAR(path.front().theta, core::kPi / 2, 1e-12);
}

TEST_F(RouteFileTest, BadPathFilesAreIoErrors) {
  const std::string where = (tmp_.path() / "bad.txt").string();
  auto error_for = [&](const std::string& text) -> std::string {
    try {
      ReadPathFile(tmp_.Write("bad.txt", text));
    } catch (const core::IoError& e) {
      return e.what();
    }
    return "";
  };
  std::string msg = error_for("0 0\n1 1\n");
  EXPECT_NE(msg.find(where + ":1: expected 7 columns"), std::string::npos) << msg;
  msg = error_for("0 0 0 0 0 0 1\n1 1 0 0 0 0 0\n");
  EXPECT_NE(msg.find(where + ":2: the quaternion is zero"), std::string::npos) << msg;
  msg = error_for("# nothing\n");
  EXPECT_NE(msg.find("holds no poses"), std::string::npos) << msg;
  EXPECT_THROW(ReadPathFile(tmp_.path() / "missing.txt"), core::IoError);
}

}  // namespace
}  // namespace retrace::io
