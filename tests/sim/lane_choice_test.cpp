// Which lane a walker of the ttc crowd model picks (sim/lane_choice.hpp): walking beside the
// route's line, keeping right of someone coming the other way (just far enough), overtaking
// someone slower, never into oncoming people, and the config's validation.

#include "sim/lane_choice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/angle.hpp"
#include "tests/support/config_key.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::ValidationErrorKey;

const Vec2 kEast(1.0, 0.0);

TEST(LaneChoice, AimKeepsTheOffsetFromTheRouteLineUpToTheTolerance) {
  LaneChoiceConfig c;
  c.tolerance = 1.0;
  // The line from (0, 0) to (10, 0); a walker 0.6 m to its left aims 0.6 m left of the waypoint.
  EXPECT_TRUE(LaneAimPoint({3.0, 0.6}, {0.0, 0.0}, {10.0, 0.0}, c).isApprox(Vec2(10.0, 0.6)));
  EXPECT_TRUE(LaneAimPoint({3.0, -2.5}, {0.0, 0.0}, {10.0, 0.0}, c).isApprox(Vec2(10.0, -1.0)));
  c.tolerance = 0.0;
  EXPECT_TRUE(LaneAimPoint({3.0, 0.6}, {0.0, 0.0}, {10.0, 0.0}, c).isApprox(Vec2(10.0, 0.0)));
}

TEST(LaneChoice, SomeoneComingTheOtherWayIsMetHeadOnOnlyInFront) {
  const LaneChoiceConfig c;
  const SocialAgent self{{0.0, 0.0}, {1.3, 0.0}, 0.2, kEast};
  const std::vector<SocialAgent> oncoming = {{{4.0, 0.1}, {-1.3, 0.0}, 0.2, -kEast}};
  EXPECT_TRUE(MeetsSomeoneHeadOn(self, kEast, 1.3, oncoming, nullptr, c));
  // The same person walking our way is followed, not avoided; behind us it does not matter.
  const std::vector<SocialAgent> same_way = {{{4.0, 0.1}, {1.0, 0.0}, 0.2, kEast}};
  EXPECT_FALSE(MeetsSomeoneHeadOn(self, kEast, 1.3, same_way, nullptr, c));
  const std::vector<SocialAgent> behind = {{{-4.0, 0.1}, {-1.3, 0.0}, 0.2, -kEast}};
  EXPECT_FALSE(MeetsSomeoneHeadOn(self, kEast, 1.3, behind, nullptr, c));
  // Too far off to meet within keep_right_time.
  const std::vector<SocialAgent> far = {{{30.0, 0.1}, {-1.3, 0.0}, 0.2, -kEast}};
  EXPECT_FALSE(MeetsSomeoneHeadOn(self, kEast, 1.3, far, nullptr, c));
  // A robot standing in the way counts, whichever way it faces.
  const SocialAgent robot{{3.0, 0.0}, {0.0, 0.0}, 0.3, kEast};
  EXPECT_TRUE(MeetsSomeoneHeadOn(self, kEast, 1.3, {}, &robot, c));
}

TEST(LaneChoice, KeepsRightJustFarEnough) {
  const LaneChoiceConfig c;
  const SocialAgent self{{0.0, 0.0}, {1.3, 0.0}, 0.2, kEast};
  const std::vector<SocialAgent> oncoming = {{{6.0, 0.2}, {-1.3, 0.0}, 0.2, -kEast}};
  const Vec2 d = KeepRight(self, kEast, 1.3, oncoming, nullptr, c);
  const double turn = std::atan2(d.y(), d.x());
  EXPECT_LT(turn, 0.0);  // to the right
  EXPECT_GE(turn, -core::DegToRad(c.keep_right_deg) - 1e-9);
  EXPECT_FALSE(MeetsSomeoneHeadOn(self, d, 1.3, oncoming, nullptr, c));
  // 5° less would not have cleared the way.
  const double less = turn + core::DegToRad(5.0);
  EXPECT_TRUE(
      MeetsSomeoneHeadOn(self, Vec2(std::cos(less), std::sin(less)), 1.3, oncoming, nullptr, c));
  // Nobody in the way: straight on.
  EXPECT_TRUE(KeepRight(self, kEast, 1.3, {}, nullptr, c).isApprox(kEast));
}

TEST(LaneChoice, OvertakesSomeoneSlowerButNotIntoOncomingPeople) {
  const LaneChoiceConfig c;
  const SpeedHeadwayConfig h;
  const SocialAgent self{{0.0, 0.0}, {1.0, 0.0}, 0.2, kEast};
  // Someone slow 1 m ahead: straight on allows (1 - 0.2) / 0.95 = 0.84 m/s; 30° to the right
  // the way is free (15° is not: the body still overlaps the path).
  std::vector<SocialAgent> others = {{{1.0, 0.0}, {0.4, 0.0}, 0.2, kEast}};
  const WalkingChoice pass = ChooseLane(self, kEast, 1.5, others, nullptr, c, h);
  EXPECT_LT(pass.direction.y(), 0.0);  // to the right first
  EXPECT_NEAR(std::atan2(pass.direction.y(), pass.direction.x()), -core::DegToRad(30.0), 1e-9);
  EXPECT_DOUBLE_EQ(pass.speed, 1.5);
  // With people coming the other way on the right and the left, it stays behind.
  others.push_back({{3.0, -0.9}, {-1.3, 0.0}, 0.2, -kEast});
  others.push_back({{3.0, 0.9}, {-1.3, 0.0}, 0.2, -kEast});
  const WalkingChoice stay = ChooseLane(self, kEast, 1.5, others, nullptr, c, h);
  EXPECT_NEAR(stay.speed, (1.0 - h.length) / h.time_gap, 1e-9);
  EXPECT_TRUE(stay.direction.isApprox(kEast));
  // Standing: no direction, no speed.
  EXPECT_EQ(ChooseLane(self, Vec2::Zero(), 1.5, others, nullptr, c, h).speed, 0.0);
}

TEST(LaneChoice, ValidateNamesTheKey) {
  EXPECT_EQ(ValidationErrorKey(LaneChoiceConfig{}), retrace::testing::kValid);
  EXPECT_EQ(ValidationErrorKey<LaneChoiceConfig>([](auto& c) { c.max_turn_deg = 100.0; }),
            "max_turn_deg");
  EXPECT_EQ(ValidationErrorKey<LaneChoiceConfig>([](auto& c) { c.turn_steps = 9; }), "turn_steps");
  EXPECT_EQ(ValidationErrorKey<LaneChoiceConfig>([](auto& c) { c.keep_right_deg = -1.0; }),
            "keep_right_deg");
  EXPECT_EQ(ValidationErrorKey<LaneChoiceConfig>([](auto& c) { c.keep_right_gap = -0.1; }),
            "keep_right_gap");
  EXPECT_EQ(ValidationErrorKey<LaneChoiceConfig>([](auto& c) { c.tolerance = -1.0; }), "tolerance");
}

}  // namespace
}  // namespace retrace::sim
