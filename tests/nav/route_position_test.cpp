#include "nav/route_position.hpp"

#include <gtest/gtest.h>

#include "core/angle.hpp"

namespace retrace::nav {
namespace {

// 20 m east, then back west 3 m north of it: the path passes its own start 3 m away.
core::Path Hairpin() {
  std::vector<core::Pose2> poses;
  for (int i = 0; i <= 40; ++i) poses.emplace_back(0.5 * i, 0.0, 0.0);
  for (int i = 0; i <= 40; ++i) poses.emplace_back(20.0 - 0.5 * i, 3.0, core::kPi);
  return core::Path(poses);
}

TEST(RouteTracker, FollowsTheStretchItIsOnBothWaysAndNeverJumpsToAPassNearby) {
  const core::Path path = Hairpin();
  RouteTracker t;
  t.Reset(path, 0, 2.0, core::Pose2(2.0, 0.0, 0.0), Travel::kUnknown);
  EXPECT_EQ(t.position().travel, Travel::kForward);  // by the heading
  // Drifting north towards the other pass, within 2 m of the first: it stays on the first.
  for (int i = 0; i <= 18; ++i) t.Update(core::Pose2(2.0, 0.1 * i, 0.0), 1.5, 2.0);
  EXPECT_NEAR(t.position().s, 2.0, 1e-9);
  EXPECT_TRUE(t.position().on_path);
  // Backward along it: the direction of travel turns after kTravelHysteresis.
  for (int i = 0; i <= 20; ++i) t.Update(core::Pose2(2.0 - 0.05 * i, 0.0, 0.0), 1.5, 2.0);
  EXPECT_EQ(t.position().travel, Travel::kBackward);
  EXPECT_NEAR(t.position().s, 1.0, 1e-6);
  // Past the start, the extended arc length goes negative.
  t.Update(core::Pose2(-0.5, 0.0, 0.0), 1.5, 2.0);
  EXPECT_NEAR(t.position().s, 0.0, 1e-9);
  EXPECT_NEAR(t.position().s_extended, -0.5, 1e-9);
}

TEST(RouteTracker, WaitsOffThePathAndKeepsItsDirectionWhenItRejoinsAhead) {
  const core::Path path = Hairpin();
  RouteTracker t;
  t.Reset(path, 0, 10.0, core::Pose2(10.0, 0.0, core::kPi), Travel::kBackward);
  // A detour 5 m south from x = 10 to x = 14: off the path, the place waits.
  for (int i = 0; i <= 16; ++i) t.Update(core::Pose2(10.0 + 0.25 * i, -5.0, 0.0), 1.5, 2.0);
  EXPECT_FALSE(t.position().on_path);
  EXPECT_NEAR(t.position().s, 10.0, 1e-9);
  EXPECT_GT(t.position().off_path_driven, 4.0);
  // Back on it 4 m ahead: the place moves there, but where it rejoined says nothing of the
  // direction of travel.
  t.Update(core::Pose2(14.0, -0.5, 0.0), 1.5, 2.0);
  EXPECT_TRUE(t.position().on_path);
  EXPECT_NEAR(t.position().s, 14.0, 1e-6);
  EXPECT_EQ(t.position().travel, Travel::kBackward);
}

TEST(RouteTracker, TravelOfAHeadingAgainstThePath) {
  const core::Path path = Hairpin();
  EXPECT_EQ(TravelOf(path, 5.0, 0.3), Travel::kForward);
  EXPECT_EQ(TravelOf(path, 5.0, core::kPi - 0.3), Travel::kBackward);
  EXPECT_EQ(TravelOf(path, 5.0, core::kPi / 2), Travel::kUnknown);
  EXPECT_EQ(TravelOf(path, 30.0, core::kPi), Travel::kForward);  // the way back runs west
  EXPECT_EQ(TravelOf(core::Path({core::Pose2(1, 1, 0)}), 0.0, 0.0), Travel::kUnknown);
}

}  // namespace
}  // namespace retrace::nav
