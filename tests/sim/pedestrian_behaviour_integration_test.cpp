// How people of each behaviour toward the robot (sim/pedestrian_behaviour.hpp) meet it: each
// behaviour's signature in the distance it keeps, the speed it walks at and the time it spends near
// the robot, against a regular walker in the same encounter (seeds 1-3, both crowd models).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/pedestrian_behaviour.hpp"
#include "sim/pedestrians.hpp"
#include "sim/physics_world.hpp"
#include "sim/robot.hpp"
#include "tests/sim/add_box.hpp"
#include "tests/support/pedestrian_group.hpp"

namespace retrace::sim::pedestrian_behaviour_integration_test {

using retrace::testing::Group;
using test_geometry::AddBox;

// What one person did in an encounter with the robot.
struct Encounter {
  double min_gap = 1e9;     // m between the edges
  double near_time = 0.0;   // s with the edges within 1.5 m
  double stood_time = 0.0;  // s slower than 0.1 m/s while the robot's edge was within 3 m
  double mean_speed = 0.0;  // m/s over the run
  double ahead_time = 0.0;  // s in front of the robot (within 30° of its heading), edges < 1 m
  double final_gap = 0.0;   // m between the edges at the end
  int reactions = 0;
};

// One person walks from x = -10 towards x = +12 along y = 0.3 in a 12 m wide hall; the robot
// starts at x = 3 facing the person (yaw pi) and drives at robot_speed (m/s) for `seconds`.
Encounter Meet(RobotBehaviour behaviour, CrowdModel model, double robot_speed, double seconds,
               std::uint64_t seed) {
  StaticGeometry g;
  AddBox(g, -15.2, -6.2, 15.2, -6.0);
  AddBox(g, -15.2, 6.0, 15.2, 6.2);
  AddBox(g, -15.2, -6.0, -15.0, 6.0);
  AddBox(g, 15.0, -6.0, 15.2, 6.0);
  PhysicsWorld world(g);
  const RobotConfig rc;
  Robot robot(rc, g, core::Pose2(3.0, 0.0, core::kPi), world);
  auto group =
      Group(1, {-10.01, 0.29}, {-9.99, 0.31}, PedestrianMode::kLoop, {{12.0, 0.3}, {-12.0, 0.3}});
  group.speed_std = 0.0;
  group.behaviour = behaviour;
  CrowdConfig config;
  config.model = model;
  config.loop_spread = 0.0;
  Pedestrians crowd({group}, config, g, core::Rng(seed), {}, world);
  Encounter out;
  const int steps = static_cast<int>(std::lround(seconds / world.time_step()));
  const double dt = world.time_step();
  for (int step = 0; step < steps; ++step) {
    robot.SetCommand({robot_speed, 0.0});
    robot.Actuate(world);
    crowd.Update(world);
    world.Step();
    const DynamicCircle c = world.PedestrianCircles()[0];
    const core::Pose2 X_WR = robot.Pose(world);
    const core::Vec2 d = c.center - X_WR.translation();
    const double gap = d.norm() - c.radius - rc.radius;
    const double speed = world.PedestrianVelocity(crowd.status()[0].id).norm();
    out.min_gap = std::min(out.min_gap, gap);
    if (gap < 1.5) out.near_time += dt;
    if (gap < 3.0 && speed < 0.1) out.stood_time += dt;
    const core::Vec2 heading(std::cos(X_WR.theta), std::sin(X_WR.theta));
    if (gap < 1.0 && d.normalized().dot(heading) > std::cos(core::kPi / 6.0)) out.ahead_time += dt;
    out.mean_speed += speed / steps;
    out.final_gap = gap;
  }
  out.reactions = crowd.status()[0].reactions;
  return out;
}

// The mean of `f` over seeds 1-3 for one behaviour and model.
template <class F>
double OverSeeds(RobotBehaviour b, CrowdModel m, double robot_speed, double seconds, F f) {
  double sum = 0.0;
  for (std::uint64_t seed : {1, 2, 3}) sum += f(Meet(b, m, robot_speed, seconds, seed));
  return sum / 3.0;
}

class BehaviourTest : public ::testing::TestWithParam<CrowdModel> {};

TEST_P(BehaviourTest, ImpassivePassesCloserThanRegularWithoutSlowingDown) {
  auto gap = [](const Encounter& e) { return e.min_gap; };
  auto speed = [](const Encounter& e) { return e.mean_speed; };
  const double regular = OverSeeds(RobotBehaviour::kRegular, GetParam(), 0.0, 15.0, gap);
  const double impassive = OverSeeds(RobotBehaviour::kImpassive, GetParam(), 0.0, 15.0, gap);
  EXPECT_LT(impassive, regular - 0.2);
  EXPECT_GE(OverSeeds(RobotBehaviour::kImpassive, GetParam(), 0.0, 15.0, speed),
            OverSeeds(RobotBehaviour::kRegular, GetParam(), 0.0, 15.0, speed) - 0.02);
}

TEST_P(BehaviourTest, SurprisedStopsNearTheRobotForAWhile) {
  auto stood = [](const Encounter& e) { return e.stood_time; };
  EXPECT_LT(OverSeeds(RobotBehaviour::kRegular, GetParam(), 0.0, 15.0, stood), 0.3);
  const double surprised = OverSeeds(RobotBehaviour::kSurprised, GetParam(), 0.0, 15.0, stood);
  EXPECT_GT(surprised, 2.0);  // surprised_time 3 s, less the time it takes to stop
  EXPECT_EQ(Meet(RobotBehaviour::kSurprised, GetParam(), 0.0, 15.0, 1).reactions, 1);
}

TEST_P(BehaviourTest, CuriousComesCloseAndFollowsTheRobot) {
  // The robot drives on at 0.5 m/s; the curious person turns round and follows it.
  auto near = [](const Encounter& e) { return e.near_time; };
  const double regular = OverSeeds(RobotBehaviour::kRegular, GetParam(), 0.5, 20.0, near);
  const double curious = OverSeeds(RobotBehaviour::kCurious, GetParam(), 0.5, 20.0, near);
  EXPECT_GT(curious, regular + 8.0);  // curious_time 15 s
  auto gap = [](const Encounter& e) { return e.min_gap; };
  EXPECT_LT(OverSeeds(RobotBehaviour::kCurious, GetParam(), 0.5, 20.0, gap), 1.0);
}

TEST_P(BehaviourTest, ScaredKeepsAWiderBerthAndWalksAway) {
  auto gap = [](const Encounter& e) { return e.min_gap; };
  const double regular = OverSeeds(RobotBehaviour::kRegular, GetParam(), 0.0, 15.0, gap);
  const double scared = OverSeeds(RobotBehaviour::kScared, GetParam(), 0.0, 15.0, gap);
  EXPECT_GT(scared, regular + 0.5);
  EXPECT_GT(scared, 1.2);  // outside Hall's personal zone
}

TEST_P(BehaviourTest, ThreateningStepsIntoTheRobotsPath) {
  // The robot stands facing -x; the threatening person (noticing it about 7 s in) plants itself
  // in front of it for most of threatening_time (8 s).
  auto ahead = [](const Encounter& e) { return e.ahead_time; };
  EXPECT_LT(OverSeeds(RobotBehaviour::kRegular, GetParam(), 0.0, 25.0, ahead), 0.5);
  EXPECT_GT(OverSeeds(RobotBehaviour::kThreatening, GetParam(), 0.0, 25.0, ahead), 5.0);
  auto gap = [](const Encounter& e) { return e.min_gap; };
  EXPECT_LT(OverSeeds(RobotBehaviour::kThreatening, GetParam(), 0.0, 25.0, gap), 0.6);
}

INSTANTIATE_TEST_SUITE_P(BothModels, BehaviourTest,
                         ::testing::Values(CrowdModel::kSocialForce, CrowdModel::kTtc),
                         [](const auto& model) {
                           return model.param == CrowdModel::kTtc ? std::string("Ttc")
                                                                  : std::string("SocialForce");
                         });

}  // namespace retrace::sim::pedestrian_behaviour_integration_test
