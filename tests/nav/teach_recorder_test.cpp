#include "nav/teach_recorder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/angle.hpp"
#include "core/twist.hpp"
#include "tests/support/fake_scan.hpp"

namespace retrace::nav {
namespace {

using core::Pose2;

void ExpectPoseNear(const Pose2& a, const Pose2& b, double tol = 1e-9) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(core::AngleDiff(a.theta, b.theta), 0.0, tol);
}

// 360 beams all round, reading the distance to the vertical wall x = 12.03 in O (or +inf).
core::LaserScan WallScan(const Pose2& X_OR) {
  core::LaserScan scan;
  scan.angle_min = -core::kPi;
  scan.angle_increment = core::DegToRad(1.0);
  scan.range_min = 0.05;
  scan.range_max = 30.0;
  for (int i = 0; i < 360; ++i) {
    const double a = X_OR.theta + scan.angle_min + i * scan.angle_increment;
    const double r = std::cos(a) > 1e-6 ? (12.03 - X_OR.x) / std::cos(a) : 1e9;
    scan.ranges.push_back(r <= 30.0 ? static_cast<float>(r)
                                    : std::numeric_limits<float>::infinity());
  }
  return scan;
}

// Drives from X_OR0 straight on and in an arc, ticking odometry every 0.02 m, feeding the
// recorder; closes a map after `close_after` ticks (if > 0). Returns all source poses.
std::vector<Pose2> DriveAndRecord(TeachRecorder& recorder, const Pose2& X_OR0, int ticks,
                                  int close_after, std::vector<Pose2>* switch_X_OR) {
  std::vector<Pose2> poses;
  Pose2 X_OR = X_OR0;
  for (int t = 0; t < ticks; ++t) {
    recorder.OnPose(X_OR);
    recorder.OnScan(WallScan(X_OR));
    poses.push_back(X_OR);
    if (close_after > 0 && (t + 1) % close_after == 0) {
      recorder.CloseMap();
      if (switch_X_OR != nullptr) switch_X_OR->push_back(X_OR);
    }
    X_OR = core::IntegrateOdometry(X_OR, {0.02, t % 100 < 50 ? 0.0 : 0.004});
  }
  return poses;
}

TEST(TeachRecorder, NextMapStartsAtIdentityAndTheSwitchPoseIsThePoseAtTheSwitch) {
  TeachRecorder recorder(MapperConfig{}, RobotGeometry{});
  const Pose2 X_OM0(1.0, 2.0, 0.3);
  const std::vector<Pose2> poses = DriveAndRecord(recorder, X_OM0, 150, 0, nullptr);
  const Pose2 X_OS = poses.back();
  ExpectPoseNear(recorder.pose(), X_OM0.Inverse() * X_OS);
  recorder.CloseMap();
  EXPECT_EQ(recorder.map_index(), 1u);
  EXPECT_EQ(recorder.pose(), Pose2::Identity());
  ASSERT_EQ(recorder.closed_maps().size(), 1u);
  const PartialMap& map0 = recorder.closed_maps()[0];
  ExpectPoseNear(map0.X_MS, X_OM0.Inverse() * X_OS);
  ASSERT_FALSE(map0.path.empty());
  EXPECT_EQ(map0.path.front(), Pose2::Identity());  // the map's start
  EXPECT_EQ(map0.path.back(), map0.X_MS);           // the path ends at the switch pose

  // The next poses are in map 1, whose origin is the switch pose; eq. (1) links the maps.
  const Pose2 X_OR = core::IntegrateOdometry(X_OS, {0.3, 0.1});
  recorder.OnPose(X_OR);
  ExpectPoseNear(recorder.pose(), X_OS.Inverse() * X_OR);
  ExpectPoseNear(recorder.pose(), map0.X_MS.Inverse() * (X_OM0.Inverse() * X_OR));
  EXPECT_TRUE(recorder.OnScan(WallScan(X_OR)));  // the first scan of a map is a keyframe
}

TEST(TeachRecorder, PathsAndMapsAreInTheirOwnFrames) {
  TeachRecorder recorder(MapperConfig{}, RobotGeometry{});
  const Pose2 X_OM0(-3.0, 0.5, -0.2);
  std::vector<Pose2> switches;
  const std::vector<Pose2> poses = DriveAndRecord(recorder, X_OM0, 400, 130, &switches);
  const TeachBundle bundle = recorder.Finish();
  ASSERT_EQ(switches.size(), 3u);  // after ticks 130, 260 and 390
  ASSERT_EQ(bundle.maps.size(), 4u);
  std::vector<Pose2> origins{X_OM0, switches[0], switches[1], switches[2]};
  for (std::size_t k = 0; k < bundle.maps.size(); ++k) {
    const PartialMap& map = bundle.maps[k];
    ASSERT_FALSE(map.path.empty()) << k;
    // Each keyframe, mapped back to O through the map's origin, is one of the driven poses.
    for (const Pose2& X_MR : map.path.poses()) {
      const Pose2 X_OR = origins[k] * X_MR;
      double best = 1e9;
      for (const Pose2& p : poses) best = std::min(best, core::Distance(p, X_OR));
      EXPECT_LT(best, 1e-9) << "map " << k;
    }
    EXPECT_EQ(map.path.front(), Pose2::Identity()) << k;  // the map's start
    EXPECT_EQ(map.path.back(), map.X_MS) << k;
    // Consecutive keyframes are 0.5 m or 5 degrees apart (but for the start and the switch).
    for (std::size_t i = 2; i + 1 < map.path.size(); ++i) {
      const bool far = core::Distance(map.path[i], map.path[i - 1]) >= 0.5 - 1e-9;
      const bool turned = std::abs(core::AngleDiff(map.path[i].theta, map.path[i - 1].theta)) >=
                          core::DegToRad(5.0) - 1e-9;
      EXPECT_TRUE(far || turned) << "map " << k << " keyframe " << i;
    }
    // The wall x = 12.03 in O appears where map k's frame puts it.
    const Pose2 X_MO = origins[k].Inverse();
    const core::Vec2 wall_M = X_MO * core::Vec2(12.03, origins[k].y);
    const core::OccupancyGrid& grid = map.grid;
    EXPECT_GT(grid.Probability(grid.WorldToCell(wall_M)), 0.65) << "map " << k;
  }
  const Pose2 X_OS_last = poses.back();
  ExpectPoseNear(bundle.maps.back().X_MS, switches[2].Inverse() * X_OS_last);
}

TEST(TeachRecorder, SingleMapModeGivesOneMap) {
  TeachRecorder recorder(MapperConfig{}, RobotGeometry{});
  const std::vector<Pose2> poses = DriveAndRecord(recorder, Pose2(), 200, 0, nullptr);
  const TeachBundle bundle = recorder.Finish();
  ASSERT_EQ(bundle.maps.size(), 1u);
  ExpectPoseNear(bundle.maps[0].X_MS, poses.back());
  EXPECT_GT(bundle.maps[0].path.size(), 5u);
}

TEST(TeachRecorder, ScansBeforeTheFirstPoseAreIgnored) {
  TeachRecorder recorder(MapperConfig{}, RobotGeometry{});
  EXPECT_FALSE(recorder.OnScan(WallScan(Pose2())));
  EXPECT_TRUE(recorder.mapper().path().empty());
  recorder.OnPose(Pose2(5.0, 5.0, 1.0));
  EXPECT_EQ(recorder.pose(), Pose2::Identity());
  EXPECT_TRUE(recorder.OnScan(WallScan(Pose2(5.0, 5.0, 1.0))));
}

// A room 16 m × 10 m with two pillars: every direction is constrained everywhere.
std::vector<testing::Segment> RoomWithPillars() {
  std::vector<testing::Segment> faces;
  auto ring = [&](std::vector<core::Vec2> v) {
    for (std::size_t i = 0; i < v.size(); ++i) faces.push_back({v[i], v[(i + 1) % v.size()]});
  };
  ring({{-8.03, -5.07}, {8.04, -5.07}, {8.04, 5.03}, {-8.03, 5.03}});
  ring({{-3.07, -0.93}, {-1.96, -0.93}, {-1.96, 0.96}, {-3.07, 0.96}});
  ring({{2.04, 1.53}, {3.03, 1.53}, {3.03, 2.47}, {2.04, 2.47}});
  return faces;
}

TEST(TeachRecorder, ScanMatchingCorrectsDriftingOdometryAndKeepsEquationOne) {
  // Truth drives a loop round the first pillar; odometry sees every step 3 % long and turning
  // 0.4 degrees more (a wheel-radius and a track-width error), so its pose drifts away.
  const std::vector<testing::Segment> faces = RoomWithPillars();
  TeachRecorder plain(MapperConfig{}, RobotGeometry{});
  TeachRecorder matched(MapperConfig{}, RobotGeometry{}, ScanMatcherConfig{});
  Pose2 X_WR(-5.0, -3.0, 0.0);
  Pose2 X_OR = Pose2::Identity();
  const Pose2 X_WO = X_WR;  // odometry starts at the truth
  std::vector<Pose2> truth;
  std::vector<Pose2> plain_poses;
  std::vector<Pose2> matched_poses;
  for (int t = 0; t < 1400; ++t) {
    for (TeachRecorder* r : {&plain, &matched}) {
      r->OnPose(X_OR);
      r->OnScan(testing::FakeScan(testing::ScanSpec{}, X_WR,
                                  [&](const core::Vec2& o, const core::Vec2& d) {
                                    return testing::NearestSegment(o, d, faces);
                                  }));
    }
    truth.push_back(X_WR);
    plain_poses.push_back(plain.pose());
    matched_poses.push_back(matched.pose());
    if (t == 900) {
      plain.CloseMap();
      matched.CloseMap();
    }
    // A rounded rectangle: straight, then a quarter turn, four times over.
    const double omega = (t % 350) < 250 ? 0.0 : core::kPi / 2.0 / 100.0;
    const double step = (t % 350) < 250 ? 0.02 : 0.01;
    X_WR = core::IntegrateOdometry(X_WR, {step, omega});
    X_OR = core::IntegrateOdometry(X_OR, {1.03 * step, omega + core::DegToRad(0.4) / 100.0});
  }
  // Map 0's poses against the truth, both from the start: the matched ones stay within a few
  // centimetres, odometry's drift by two decimetres.
  double plain_worst = 0.0;
  double matched_worst = 0.0;
  for (int t = 0; t <= 900; ++t) {
    const Pose2 X_MR_true = X_WO.Inverse() * truth[static_cast<std::size_t>(t)];
    plain_worst =
        std::max(plain_worst, core::Distance(plain_poses[static_cast<std::size_t>(t)], X_MR_true));
    matched_worst = std::max(matched_worst,
                             core::Distance(matched_poses[static_cast<std::size_t>(t)], X_MR_true));
  }
  EXPECT_GT(plain_worst, 0.2);
  EXPECT_LT(matched_worst, 0.05);
  const auto& counts = matched.match_counts();
  EXPECT_EQ(counts[static_cast<std::size_t>(MatchVerdict::kEmptyMap)],
            2);  // each map's first keyframe
  EXPECT_GT(counts[static_cast<std::size_t>(MatchVerdict::kMatched)], 30);
  EXPECT_EQ(plain.match_counts(), (std::array<int, 5>{}));

  // Map 1 starts at the identity, and its origin is map 0's switch pose (eq. 1).
  const TeachBundle bundle = matched.Finish();
  ASSERT_EQ(bundle.maps.size(), 2u);
  ExpectPoseNear(bundle.maps[0].X_MS, matched_poses[900]);
  EXPECT_EQ(bundle.maps[1].path.front(), Pose2::Identity());
  const Pose2 X_M0R = bundle.maps[0].X_MS * matched_poses.back();  // map 1's last pose in map 0
  const Pose2 X_M0R_true = X_WO.Inverse() * truth.back();
  EXPECT_LT(core::Distance(X_M0R, X_M0R_true), 0.1);
}

}  // namespace
}  // namespace retrace::nav
