#include "nav/navigator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "core/rng.hpp"
#include "tests/nav/localizer_room.hpp"

namespace retrace::nav {
namespace {

using core::Pose2;

// On the room's drive circle (centre (6, 4.5), radius 2.5 m, counter-clockwise), the pose at
// angle phi from the start (6, 2).
Pose2 OnCircle(double phi) { return {6.0 + 2.5 * std::sin(phi), 4.5 - 2.5 * std::cos(phi), phi}; }

core::Path Arc(double from, double to, const Pose2& X_MW) {
  std::vector<Pose2> poses;
  for (double phi = from; phi < to; phi += 0.04) poses.push_back(X_MW * OnCircle(phi));
  poses.push_back(X_MW * OnCircle(to));
  return core::Path(std::move(poses));
}

// The room rasterised in a frame M placed at X_WM.
core::OccupancyGrid RoomIn(const Pose2& X_WM) {
  core::OccupancyGrid g(230, 230, 0.1, core::Vec2(-8.0, -8.0));  // [-8, 15] m: either frame
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const core::Vec2 c = X_WM * g.CellToWorld({x, y});
      bool occ = false;
      for (const testing::Rect& r : testing_room::RoomGeometry()) {
        occ = occ || (c.x() >= r.x0 && c.x() <= r.x1 && c.y() >= r.y0 && c.y() <= r.y1);
      }
      g.SetProbability({x, y}, occ ? 0.95 : 0.05);
    }
  }
  return g;
}

// A loop of two maps: map 0 holds the first half of the circle (M_0 = W), map 1 the second half
// (M_1 placed at the switch pose). The bundle's switch pose is off by `error` m along its
// heading, as a lap's drift leaves it: the wrap by the chain carries the estimate that far wrong.
TeachBundle LoopOfTwo(double error) {
  const Pose2 X_WM1 = OnCircle(std::numbers::pi);
  TeachBundle b;
  b.maps.resize(2);
  b.maps[0].grid = RoomIn(Pose2::Identity());
  b.maps[0].path = Arc(0.0, std::numbers::pi, Pose2::Identity());
  b.maps[0].X_MS = X_WM1 * Pose2(error, 0.0, 0.0);
  b.maps[1].grid = RoomIn(X_WM1);
  b.maps[1].path = Arc(std::numbers::pi, 2.0 * std::numbers::pi, X_WM1.Inverse());
  b.maps[1].X_MS = b.maps[1].path.poses().back();
  b.linked = true;  // no revisit edge: the wrap goes by the chain
  return b;
}

// Drives from 2.4 m before the end of map 1's path across the wrap into map 0 (not to map 0's
// end, where the bundle's wrong switch pose would carry the estimate 0.8 m off into map 1),
// localizing on scans of the room. The wrap's transform is 0.8 m off and may be off by σ = 0.94 m
// (drift 0.12 × the 15.7 m route / 2).
struct WrapDrive {
  static constexpr int kSteps = 300;  // 7.5 m: 2.4 m to the wrap, 5.1 m on path 0
  const Pose2 X_WM1 = OnCircle(std::numbers::pi);
  testing_room::Drive drive{7};
  Navigator nav;

  explicit WrapDrive(double settle_wait)
      : nav(testing_room::TestConfig(), PathFollowerConfig{}, testing_room::TestRobot(),
            LoopOfTwo(0.8), Server(settle_wait), Link(), true, core::Rng(7)) {
    drive.X_WR = OnCircle(2.0 * std::numbers::pi - 0.96);
    nav.Start(1, X_WM1.Inverse() * drive.X_WR, 0.05, 0.02);
  }
  static MapServerConfig Server(double settle_wait) {
    MapServerConfig server;
    server.settle_wait = settle_wait;
    return server;
  }
  static RouteLinkConfig Link() {
    RouteLinkConfig link;
    link.drift = 0.12;
    return link;
  }
  // Step i of the drive: odometry, a scan every second step, a control tick every fourth.
  std::optional<NavigatorTick> Step(int i) {
    nav.OnOdometry(drive.Step());
    if (i % 2 == 0) {
      nav.OnScan(testing_room::MakeScan(drive.rects, {},
                                        drive.X_WR * testing_room::TestRobot().X_RL, drive.rng));
    }
    if (i % 4 != 0) return std::nullopt;
    return nav.OnControlTick(0.1);
  }
};

// The switch settles in map 0 before it commits, so the estimate the robot drives on is never
// far from the truth in the map it is in, and never jumps.
TEST(Navigator, AnUncertainWrapSettlesInTheMapItEntersBeforeItCommits) {
  WrapDrive w(MapServerConfig{}.settle_wait);
  int settling_ticks = 0;
  bool wrapped = false;
  double worst = 0.0;
  for (int i = 0; i < WrapDrive::kSteps; ++i) {
    const std::optional<NavigatorTick> tick = w.Step(i);
    if (!tick) continue;
    wrapped = wrapped || tick->wrapped;
    if (w.nav.settling()) {
      ++settling_ticks;
      EXPECT_EQ(w.nav.server().index(), 1u) << "the estimate stays in the map left while settling";
    }
    const Pose2 X_WM = w.nav.server().index() == 0 ? Pose2::Identity() : w.X_WM1;
    const double error = core::Distance(w.nav.Estimate(), X_WM.Inverse() * w.drive.X_WR);
    worst = std::max(worst, error);
    EXPECT_LT(error, 0.3) << "tick " << i / 4 << " in map " << w.nav.server().index();
  }
  EXPECT_TRUE(wrapped);
  EXPECT_GT(settling_ticks, 0);
  EXPECT_EQ(w.nav.server().index(), 0u);
  EXPECT_FALSE(w.nav.settling());
  RecordProperty("worst_error_m", std::to_string(worst));
}

// The same wrap made at once, as before settling existed (settle_wait 0 commits at the first
// tick): the estimate enters map 0 as wrong as the chain is. This is what the test above guards.
TEST(Navigator, AWrapThatDoesNotSettleCarriesTheChainsErrorIntoTheEstimate) {
  WrapDrive w(0.0);
  double error_at_wrap = 0.0;
  for (int i = 0; i < WrapDrive::kSteps && error_at_wrap == 0.0; ++i) {
    const std::optional<NavigatorTick> tick = w.Step(i);
    if (tick && tick->wrapped) error_at_wrap = core::Distance(w.nav.Estimate(), w.drive.X_WR);
  }
  EXPECT_GT(error_at_wrap, 0.5);
}

}  // namespace
}  // namespace retrace::nav
