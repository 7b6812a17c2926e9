#include "nav/teach_bundle.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/occupancy_grid.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::nav {
namespace {

namespace fs = std::filesystem;
using core::Pose2;
using TeachBundleTest = retrace::testing::TempDirTest;

enum class CellClass { kFree, kUnknown, kOccupied };

CellClass ClassOf(const core::OccupancyGrid& grid, core::CellIndex c) {
  const double p = grid.Probability(c);
  return p > 0.65 ? CellClass::kOccupied : p < 0.196 ? CellClass::kFree : CellClass::kUnknown;
}

// Map k: a grid with a pattern of all three classes (log-odds as the mapper leaves them), a
// curved path in its own frame and a switch pose at the path's end.
PartialMap MakeMap(int k) {
  PartialMap map;
  map.grid = core::OccupancyGrid(37 + k, 23, 0.1, core::Vec2(-1.8 - 0.1 * k, -0.7));
  for (int y = 0; y < map.grid.height(); ++y) {
    for (int x = 0; x < map.grid.width(); ++x) {
      const int m = (x * 7 + y * 3 + k) % 5;
      map.grid.SetLogOdds({x, y}, m == 0   ? 8.0f
                                  : m == 1 ? 2.1f
                                  : m == 2 ? -8.0f
                                  : m == 3 ? -1.9f
                                           : 0.0f);
    }
  }
  Pose2 p = Pose2::Identity();
  for (int i = 0; i < 12 + k; ++i) {
    map.path.PushBack(p);
    p = p * Pose2(0.5, 0.0, 0.1 * (k + 1) + 1e-3 * i);
  }
  map.X_MS = map.path.back();
  return map;
}

TeachBundle MakeBundle(int n) {
  TeachBundle bundle;
  for (int k = 0; k < n; ++k) bundle.maps.push_back(MakeMap(k));
  return bundle;
}

// The message of the IoError that reading `dir` throws ("" if none).
std::string ReadError(const fs::path& dir) {
  try {
    ReadTeachBundle(dir);
  } catch (const core::IoError& e) {
    return e.what();
  }
  return "";
}

TEST_F(TeachBundleTest, RoundTripKeepsClassesPathsAndSwitchPoses) {
  const TeachBundle bundle = MakeBundle(3);
  const fs::path dir = tmp_.path() / "teach";
  WriteTeachBundle(dir, bundle);
  for (const char* f : {"maps/ogm_0.yaml", "maps/ogm_0.pgm", "maps/ogm_2.yaml", "maps/ogm_2.pgm",
                        "paths/path_0.txt", "paths/path_2.txt", "switch_poses.txt",
                        "last_pose_0.txt", "last_pose_2.txt", "sub_map_num.txt"}) {
    EXPECT_TRUE(fs::is_regular_file(dir / f)) << f;
  }
  EXPECT_EQ(tmp_.Read(dir / "sub_map_num.txt"), "3\n");
  EXPECT_EQ(tmp_.Read(dir / "switch_poses.txt").front(), '#');
  EXPECT_FALSE(fs::exists(dir / "maps/ogm_3.yaml"));

  const TeachBundle read = ReadTeachBundle(dir);
  ASSERT_EQ(read.maps.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const PartialMap& a = bundle.maps[k];
    const PartialMap& b = read.maps[k];
    ASSERT_EQ(a.grid.width(), b.grid.width()) << k;
    ASSERT_EQ(a.grid.height(), b.grid.height()) << k;
    EXPECT_NEAR(a.grid.resolution(), b.grid.resolution(), 1e-12);
    EXPECT_NEAR(a.grid.origin().x(), b.grid.origin().x(), 1e-9);
    EXPECT_NEAR(a.grid.origin().y(), b.grid.origin().y(), 1e-9);
    int differing = 0;
    for (int y = 0; y < a.grid.height(); ++y) {
      for (int x = 0; x < a.grid.width(); ++x) {
        differing += ClassOf(a.grid, {x, y}) != ClassOf(b.grid, {x, y});
      }
    }
    EXPECT_EQ(differing, 0) << "map " << k;
    ASSERT_EQ(a.path.size(), b.path.size()) << k;
    for (std::size_t i = 0; i < a.path.size(); ++i) {
      EXPECT_NEAR(a.path[i].x, b.path[i].x, 1e-9);
      EXPECT_NEAR(a.path[i].y, b.path[i].y, 1e-9);
      EXPECT_NEAR(core::AngleDiff(a.path[i].theta, b.path[i].theta), 0.0, 1e-9);
    }
    EXPECT_EQ(a.X_MS, b.X_MS) << k;  // shortest round-trip numbers: exact
  }
}

TEST_F(TeachBundleTest, RevisitEdgesRoundTripAndOldFoldersAreNotLinked) {
  TeachBundle bundle = MakeBundle(3);
  bundle.revisits = {{0, 2, 1.5, 7.25, core::Pose2(0.3, -2.0, 0.125)}};
  bundle.linked = true;
  const fs::path dir = tmp_.path() / "teach";
  WriteTeachBundle(dir, bundle);
  const TeachBundle read = ReadTeachBundle(dir);
  EXPECT_TRUE(read.linked);
  ASSERT_EQ(read.revisits.size(), 1u);
  EXPECT_EQ(read.revisits[0].a, 0u);
  EXPECT_EQ(read.revisits[0].b, 2u);
  EXPECT_EQ(read.revisits[0].s_a, 1.5);
  EXPECT_EQ(read.revisits[0].s_b, 7.25);
  EXPECT_EQ(read.revisits[0].X_ab, bundle.revisits[0].X_ab);
  // A folder written before the route graph has no revisits.txt: read unlinked (the map
  // server links it when it loads it).
  fs::remove(dir / "revisits.txt");
  EXPECT_FALSE(ReadTeachBundle(dir).linked);
  // A bad line names the file and the line.
  tmp_.Write(dir / "revisits.txt", "# edges\n0 3 1 2 0 0 0\n");
  EXPECT_NE(ReadError(dir).find("revisits.txt:2: map index 3 is not one of the 3 maps"),
            std::string::npos)
      << ReadError(dir);
  tmp_.Write(dir / "revisits.txt", "1 1 1 2 0 0 0\n");
  EXPECT_NE(ReadError(dir).find("map a must come before map b"), std::string::npos);
}

TEST_F(TeachBundleTest, LastPoseFilesUseAutoNavisLayout) {
  TeachBundle bundle = MakeBundle(1);
  bundle.maps[0].X_MS = Pose2(1.5, -2.25, 0.5);
  WriteTeachBundle(tmp_.path(), bundle);
  EXPECT_EQ(tmp_.Read("last_pose_0.txt"), "1.5 -2.25 0.5\n");
  EXPECT_NE(tmp_.Read("switch_poses.txt").find("\n1.5 -2.25 0.5\n"), std::string::npos);
}

TEST_F(TeachBundleTest, RewritingAShorterBundleRemovesTheStaleMaps) {
  WriteTeachBundle(tmp_.path(), MakeBundle(3));
  WriteTeachBundle(tmp_.path(), MakeBundle(2));
  EXPECT_FALSE(fs::exists(tmp_.path() / "maps/ogm_2.yaml"));
  EXPECT_FALSE(fs::exists(tmp_.path() / "paths/path_2.txt"));
  EXPECT_FALSE(fs::exists(tmp_.path() / "last_pose_2.txt"));
  EXPECT_EQ(ReadTeachBundle(tmp_.path()).maps.size(), 2u);
}

TEST_F(TeachBundleTest, MissingPathFileGivesOneClearError) {
  WriteTeachBundle(tmp_.path(), MakeBundle(2));
  fs::remove(tmp_.path() / "paths/path_1.txt");
  const std::string message = ReadError(tmp_.path());
  EXPECT_NE(message.find("cannot read teach bundle"), std::string::npos) << message;
  EXPECT_NE(message.find("path_1.txt: file is missing"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST_F(TeachBundleTest, WrongCountGivesOneClearError) {
  WriteTeachBundle(tmp_.path(), MakeBundle(2));
  tmp_.Write("sub_map_num.txt", "3\n");
  std::string message = ReadError(tmp_.path());
  EXPECT_NE(message.find("switch_poses.txt: holds 2 switch poses, but sub_map_num.txt says 3"),
            std::string::npos)
      << message;
  // With a third switch pose, the missing map is named.
  tmp_.Write("switch_poses.txt", "# header\n0 0 0\n1 0 0\n2 0 0\n");
  tmp_.Write("last_pose_0.txt", "0 0 0\n");
  tmp_.Write("last_pose_1.txt", "1 0 0\n");
  message = ReadError(tmp_.path());
  EXPECT_NE(message.find("ogm_2.yaml: file is missing"), std::string::npos) << message;
  tmp_.Write("sub_map_num.txt", "two\n");
  message = ReadError(tmp_.path());
  EXPECT_NE(message.find("sub_map_num.txt:1: 'two' is not a finite number"), std::string::npos)
      << message;
  tmp_.Write("sub_map_num.txt", "0\n");
  message = ReadError(tmp_.path());
  EXPECT_NE(message.find("must be a positive integer"), std::string::npos) << message;
}

TEST_F(TeachBundleTest, GarbageLinesGiveOneClearError) {
  WriteTeachBundle(tmp_.path(), MakeBundle(2));
  const std::string path_text = tmp_.Read("paths/path_0.txt");
  tmp_.Write("paths/path_0.txt", path_text + "1 2 3 oops 0 0 1\n");
  std::string message = ReadError(tmp_.path());
  EXPECT_NE(message.find("path_0.txt:13: 'oops' is not a number"), std::string::npos) << message;
  tmp_.Write("paths/path_0.txt", path_text);
  tmp_.Write("switch_poses.txt", "# x y yaw\n0 0\n1 0 0\n");
  message = ReadError(tmp_.path());
  EXPECT_NE(message.find("switch_poses.txt:2: expected 3 numbers (x y yaw), got 2"),
            std::string::npos)
      << message;
  WriteTeachBundle(tmp_.path(), MakeBundle(2));
  tmp_.Write("last_pose_1.txt", "9 9 9\n");
  message = ReadError(tmp_.path());
  EXPECT_NE(message.find("last_pose_1.txt: disagrees with line"), std::string::npos) << message;
  WriteTeachBundle(tmp_.path(), MakeBundle(2));
  tmp_.Write("maps/ogm_1.yaml", "image: ogm_1.pgm\nresolution: fast\n");
  message = ReadError(tmp_.path());
  EXPECT_NE(message.find("ogm_1.yaml"), std::string::npos) << message;
  EXPECT_NE(message.find("cannot read teach bundle"), std::string::npos) << message;
}

TEST_F(TeachBundleTest, MissingFolderGivesOneClearError) {
  const std::string message = ReadError(tmp_.path() / "nowhere");
  EXPECT_NE(message.find("cannot read teach bundle"), std::string::npos) << message;
  EXPECT_NE(message.find("no such folder"), std::string::npos) << message;
  EXPECT_NE(ReadError(tmp_.path()).find("sub_map_num.txt: file is missing"), std::string::npos);
}

TEST_F(TeachBundleTest, WritingAnEmptyBundleOrPathThrows) {
  EXPECT_THROW(WriteTeachBundle(tmp_.path(), TeachBundle{}), core::IoError);
  TeachBundle bundle = MakeBundle(1);
  bundle.maps[0].path = core::Path();
  EXPECT_THROW(WriteTeachBundle(tmp_.path(), bundle), core::IoError);
}

}  // namespace
}  // namespace retrace::nav
