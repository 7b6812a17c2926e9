// The behaviours toward the robot (sim/pedestrian_behaviour.hpp) as pure functions: where each
// reaction goes and how fast, which behaviours react, and the config's validation. Their
// encounters with a robot are in pedestrian_behaviour_integration_test.cpp.

#include "sim/pedestrian_behaviour.hpp"

#include <gtest/gtest.h>

#include "tests/support/config_key.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::ValidationErrorKey;

TEST(RobotBehaviour, ReactionGoals) {
  const RobotBehaviourConfig c;
  const RobotDisc robot{{0.0, 0.0}, 0.3, {1.0, 0.0}, {0.0, 0.0}};
  const Vec2 p(3.0, 0.0);
  EXPECT_EQ(ReactionGoal(RobotBehaviour::kSurprised, p, 0.2, 1.3, robot, c).speed, 0.0);
  const ReactionTarget curious = ReactionGoal(RobotBehaviour::kCurious, p, 0.2, 1.3, robot, c);
  EXPECT_NEAR(curious.point.x(), 0.3 + 0.2 + c.curious_gap, 1e-12);
  EXPECT_NEAR(curious.point.y(), 0.0, 1e-12);
  const ReactionTarget scared = ReactionGoal(RobotBehaviour::kScared, p, 0.2, 1.3, robot, c);
  EXPECT_GT(scared.point.x(), p.x());
  EXPECT_EQ(scared.speed, 1.3);
  const ReactionTarget threat =
      ReactionGoal(RobotBehaviour::kThreatening, {0.0, 3.0}, 0.2, 1.3, robot, c);
  EXPECT_NEAR(threat.point.x(), 0.3 + 0.2 + c.threatening_gap, 1e-12);
  EXPECT_NEAR(threat.point.y(), 0.0, 1e-12);
  EXPECT_GT(threat.speed, 0.0);
  // On the point: at rest.
  EXPECT_NEAR(ReactionGoal(RobotBehaviour::kCurious, curious.point, 0.2, 1.3, robot, c).speed, 0.0,
              1e-12);
  EXPECT_FALSE(Reacts(RobotBehaviour::kRegular));
  EXPECT_FALSE(Reacts(RobotBehaviour::kImpassive));
  EXPECT_TRUE(Reacts(RobotBehaviour::kThreatening));
}

TEST(RobotBehaviour, ValidateNamesTheKey) {
  EXPECT_EQ(ValidationErrorKey(RobotBehaviourConfig{}), retrace::testing::kValid);
  EXPECT_EQ(ValidationErrorKey<RobotBehaviourConfig>([](auto& c) { c.notice_distance = 0.0; }),
            "notice_distance");
  EXPECT_EQ(ValidationErrorKey<RobotBehaviourConfig>([](auto& c) { c.curious_time = -1.0; }),
            "curious_time");
  EXPECT_EQ(ValidationErrorKey<RobotBehaviourConfig>([](auto& c) { c.scared_range = 0.0; }),
            "scared_range");
}

}  // namespace
}  // namespace retrace::sim
