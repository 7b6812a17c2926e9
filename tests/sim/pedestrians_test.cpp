#include "sim/pedestrians.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "io/config_yaml.hpp"
#include "sim/physics_world.hpp"
#include "sim/robot.hpp"
#include "tests/sim/rooms_and_corridor.hpp"
#include "tests/support/config_key.hpp"
#include "tests/support/pedestrian_group.hpp"

namespace retrace::sim {
namespace {

using namespace testing_floor;

using retrace::testing::kValid;
using retrace::testing::ValidationErrorKey;

std::uint64_t HashPositions(const PhysicsWorld& world) {
  std::uint64_t h = core::HashBytes(nullptr, 0);
  for (const DynamicCircle& c : world.PedestrianCircles()) {
    const double xy[2] = {c.center.x(), c.center.y()};
    h = core::HashBytes(xy, sizeof(xy), h);
  }
  return h;
}

struct CorridorResult {
  double min_gap = 1e9;  // m between robot and pedestrian surfaces
  int robot_contacts = 0;
  double robot_displacement = 0.0;
  int min_goals_past_robot = 1 << 30;
};

// A 30 m x 3 m corridor with the robot standing in the middle; 10 pedestrians walk its length
// both ways and 4 wander, for 3 minutes.
CorridorResult RunCorridorWithStandingRobot(const CrowdConfig& config) {
  StaticGeometry g;
  AddBox(g, -0.2, -1.7, 30.2, -1.5);
  AddBox(g, -0.2, 1.5, 30.2, 1.7);
  AddBox(g, -0.2, -1.5, 0.0, 1.5);
  AddBox(g, 30.0, -1.5, 30.2, 1.5);
  PhysicsWorld world(g);
  const RobotConfig rc;
  const core::Pose2 X_WR0(15.0, 0.0, 0.0);
  Robot robot(rc, g, X_WR0, world);
  const std::vector<PedestrianGroupConfig> groups = {
      Group(6, {0.5, -1.2}, {10.0, 1.2}, PedestrianMode::kLoop, {{2.0, 0.0}, {28.0, 0.0}}),
      Group(4, {20.0, -1.2}, {29.5, 1.2}, PedestrianMode::kLoop, {{28.0, 0.5}, {2.0, -0.5}}),
      Group(4, {0.5, -1.2}, {29.5, 1.2})};
  Pedestrians crowd(groups, config, g, core::Rng(5), {{X_WR0.translation(), rc.radius}}, world);
  CorridorResult result;
  for (int step = 0; step < 18000; ++step) {
    robot.SetCommand({0.0, 0.0});
    robot.Actuate(world);
    crowd.Update(world);
    world.Step();
    for (const auto& e : world.TakeCollisions()) {
      result.robot_contacts += e.kind == CollisionKind::kPedestrian;
    }
    for (const auto& c : world.PedestrianCircles()) {
      result.min_gap =
          std::min(result.min_gap,
                   (c.center - robot.Pose(world).translation()).norm() - c.radius - rc.radius);
    }
  }
  result.robot_displacement = core::Distance(robot.Pose(world), X_WR0);
  for (const auto& s : crowd.status()) {
    if (s.group < 2)
      result.min_goals_past_robot = std::min(result.min_goals_past_robot, s.goals_reached);
  }
  return result;
}

TEST(Pedestrians, KeepAwayFromARobotStandingInTheCorridor) {
  const CorridorResult r = RunCorridorWithStandingRobot(CrowdConfig{});
  RecordProperty("min_gap_to_robot", std::to_string(r.min_gap));
  RecordProperty("min_goals_past_robot", std::to_string(r.min_goals_past_robot));
  // Since the crowd was tuned to Weidmann's curve (pedestrian strength 0.5, not 2.1) people
  // press closer to each other, and in this 3 m corridor the ones behind can push a passing one
  // against the robot: GCC's build measured 0 contacts and a 0.025 m gap, Clang's 1 graze
  // (0.004 m of overlap, the robot moved 1 cm). Before the tuning: 0 contacts, gap > 0.1 m.
  // The robot term still does its job (without it, below, more than 10 contacts).
  EXPECT_LE(r.robot_contacts, 1);
  EXPECT_GT(r.min_gap, -0.01);
  EXPECT_LT(r.robot_displacement, 0.02);
  EXPECT_GE(r.min_goals_past_robot, 3) << "someone did not get past the robot";
  // Without the robot term they walk into it: the test above is not passing by luck.
  CrowdConfig ignoring;
  ignoring.social_force.robot_strength = 0.0;
  const CorridorResult blind = RunCorridorWithStandingRobot(ignoring);
  RecordProperty("contacts_when_ignoring_robot", std::to_string(blind.robot_contacts));
  EXPECT_GT(blind.robot_contacts, 10);
}

TEST(Pedestrians, CrossANarrowDoorBothWays) {
  // A 10 m x 6 m room split by a wall with a 0.9 m door; four people walk a loop through it,
  // so they meet head-on in the door.
  StaticGeometry g;
  AddBox(g, -0.2, -0.2, 10.2, 0.0);
  AddBox(g, -0.2, 6.0, 10.2, 6.2);
  AddBox(g, -0.2, 0.0, 0.0, 6.0);
  AddBox(g, 10.0, 0.0, 10.2, 6.0);
  AddBox(g, 4.9, 0.0, 5.1, 2.55);
  AddBox(g, 4.9, 3.45, 5.1, 6.0);
  PhysicsWorld world(g);
  Pedestrians crowd(
      {Group(4, {0.2, 0.2}, {4.5, 5.8}, PedestrianMode::kLoop, {{2.0, 3.0}, {8.0, 3.0}})},
      CrowdConfig{}, g, core::Rng(1), {}, world);
  double min_clearance = 1e9;
  for (int step = 0; step < 12000; ++step) {  // 2 minutes
    crowd.Update(world);
    world.Step();
    for (const auto& c : world.PedestrianCircles())
      min_clearance = std::min(min_clearance, g.Clearance(c.center));
  }
  EXPECT_GE(min_clearance, 0.3 - 0.01);
  for (const auto& s : crowd.status()) {
    // One crossing takes about 6 m / 1.34 m/s = 4.5 s; allow for waiting at the door.
    EXPECT_GE(s.goals_reached, 8) << "pedestrian " << s.id;
  }
}

TEST(Pedestrians, SameSeedGivesIdenticalPositions) {
  const StaticGeometry g = RoomsAndCorridor();
  auto run = [&](std::uint64_t seed) {
    PhysicsWorld world(g);
    Robot robot(RobotConfig{}, g, core::Pose2(12.0, 7.0, 0.0), world);
    Pedestrians crowd(RoomsAndCorridorGroups(), CrowdConfig{}, g, core::Rng(seed),
                      {{{12.0, 7.0}, 0.3}}, world);
    for (int step = 0; step < 6000; ++step) {  // 60 s
      robot.SetCommand({0.3, 0.05});
      robot.Actuate(world);
      crowd.Update(world);
      world.Step();
    }
    return HashPositions(world);
  };
  const std::uint64_t a = run(11);
  EXPECT_EQ(a, run(11));
  EXPECT_NE(a, run(12));
}

TEST(Pedestrians, SpawnKeepsClearOfTheRobotWallsAndEachOther) {
  const StaticGeometry g = RoomsAndCorridor();
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    PhysicsWorld world(g);
    const Circle robot{{5.0, 3.0}, 0.3};
    const CrowdConfig config;
    Pedestrians crowd({Group(15, {0.0, 0.0}, {11.9, 5.8})}, config, g, core::Rng(seed), {robot},
                      world);
    const auto circles = world.PedestrianCircles();
    ASSERT_EQ(circles.size(), 15u);
    for (std::size_t i = 0; i < circles.size(); ++i) {
      EXPECT_GE(g.Clearance(circles[i].center), 0.3 + config.planner.margin - 0.0708);
      EXPECT_GE((circles[i].center - robot.center).norm(), 0.6 + config.keep_clear_gap);
      EXPECT_LT(circles[i].center.x(), 11.9);
      for (std::size_t j = i + 1; j < circles.size(); ++j) {
        EXPECT_GE((circles[i].center - circles[j].center).norm(), 0.6 + config.spawn_gap);
      }
    }
  }
}

TEST(Pedestrians, DesiredSpeedsFollowTheConfiguredDistribution) {
  StaticGeometry g;
  AddBox(g, -1.0, -1.0, 0.0, 0.0);
  PhysicsWorld world(g);
  Pedestrians crowd({Group(300, {1.0, 1.0}, {41.0, 41.0})}, CrowdConfig{}, g, core::Rng(3), {},
                    world);
  double sum = 0.0, sum2 = 0.0;
  for (const auto& s : crowd.status()) {
    EXPECT_GE(s.desired_speed, 1.34 - 2 * 0.26 - 1e-12);
    EXPECT_LE(s.desired_speed, 1.34 + 2 * 0.26 + 1e-12);
    sum += s.desired_speed;
    sum2 += s.desired_speed * s.desired_speed;
  }
  const double n = static_cast<double>(crowd.size());
  const double mean = sum / n, stddev = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 1.34, 0.04);    // 3 standard errors
  EXPECT_NEAR(stddev, 0.24, 0.04);  // slightly below 0.26 because of the clipping
}

TEST(Pedestrians, RegionInsideAWallIsAClearWorldError) {
  StaticGeometry g;
  AddBox(g, 0.0, 0.0, 10.0, 10.0);
  PhysicsWorld world(g);
  try {
    Pedestrians crowd({Group(1, {2.0, 2.0}, {8.0, 8.0})}, CrowdConfig{}, g, core::Rng(1), {},
                      world);
    FAIL() << "expected WorldError";
  } catch (const core::WorldError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("pedestrian group 0"), std::string::npos) << what;
    EXPECT_NE(what.find("no free space"), std::string::npos) << what;
  }
}

TEST(Pedestrians, OvercrowdedRegionIsAClearWorldError) {
  StaticGeometry g;
  AddBox(g, -0.2, -0.2, 2.2, 0.0);
  AddBox(g, -0.2, 2.0, 2.2, 2.2);
  AddBox(g, -0.2, 0.0, 0.0, 2.0);
  AddBox(g, 2.0, 0.0, 2.2, 2.0);
  PhysicsWorld world(g);
  CrowdConfig config;
  config.max_spawn_tries = 500;
  try {
    Pedestrians crowd({Group(20, {0.0, 0.0}, {2.0, 2.0})}, config, g, core::Rng(1), {}, world);
    FAIL() << "expected WorldError";
  } catch (const core::WorldError& e) {
    EXPECT_NE(std::string(e.what()).find("too full"), std::string::npos) << e.what();
  }
}

TEST(Pedestrians, UnreachableLoopWaypointIsAWorldError) {
  StaticGeometry g = RoomsAndCorridor();
  AddBox(g, 14.0, 1.0, 17.0, 1.2);  // a closed box in the bottom-right room
  AddBox(g, 14.0, 4.0, 17.0, 4.2);
  AddBox(g, 14.0, 1.2, 14.2, 4.0);
  AddBox(g, 16.8, 1.2, 17.0, 4.0);
  PhysicsWorld world(g);
  EXPECT_THROW(Pedestrians({Group(2, {1.0, 6.2}, {23.0, 7.8}, PedestrianMode::kLoop,
                                  {{5.0, 7.0}, {15.5, 2.6}})},
                           CrowdConfig{}, g, core::Rng(1), {}, world),
               core::WorldError);
  // Outside the building: walkable, but not from inside.
  EXPECT_THROW(Pedestrians({Group(2, {1.0, 6.2}, {23.0, 7.8}, PedestrianMode::kLoop,
                                  {{5.0, 7.0}, {-3.0, 7.0}})},
                           CrowdConfig{}, g, core::Rng(1), {}, world),
               core::WorldError);
}

TEST(PedestrianGroupConfig, ValidateNamesTheKey) {
  PedestrianGroupConfig c;
  EXPECT_EQ(ValidationErrorKey(c), kValid);
  c.count = -1;
  EXPECT_EQ(ValidationErrorKey(c), "count");
  c = {};
  c.region_max = {0.5, 2.0};
  c.region_min = {0.5, 0.0};
  EXPECT_EQ(ValidationErrorKey(c), "region_max");
  c = {};
  c.mode = PedestrianMode::kLoop;
  c.waypoints = {{0.0, 0.0}};
  EXPECT_EQ(ValidationErrorKey(c), "waypoints");
  c.waypoints.push_back({1.0, 1.0});
  EXPECT_EQ(ValidationErrorKey(c), kValid);
  c = {};
  c.speed_mean = 0.0;
  EXPECT_EQ(ValidationErrorKey(c), "speed_mean");
  c = {};
  c.speed_std = -0.1;
  EXPECT_EQ(ValidationErrorKey(c), "speed_std");
  c = {};
  c.radius = 0.0;
  EXPECT_EQ(ValidationErrorKey(c), "radius");
}

TEST(PedestrianGroupConfig, YamlLoopWithOneWaypointIsRejectedWithTheKey) {
  const YAML::Node node = YAML::Load("count: 3\nmode: loop\nwaypoints: [[1, 2]]\n");
  try {
    io::ReadConfig<PedestrianGroupConfig>(node, "world.yaml");
    FAIL() << "expected ConfigError";
  } catch (const core::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("waypoints"), std::string::npos) << e.what();
  }
  const auto ok = io::ReadConfig<PedestrianGroupConfig>(
      YAML::Load("count: 3\nmode: loop\nwaypoints: [[1, 2], [3, 4]]\nspeed_mean: 1.1\n"), "w.yaml");
  EXPECT_EQ(ok.mode, PedestrianMode::kLoop);
  EXPECT_EQ(ok.waypoints.size(), 2u);
}

TEST(Pedestrians, CrowdConfigValidateNamesNestedKeys) {
  CrowdConfig c;
  EXPECT_NO_THROW(c.Validate());
  c.social_force.fov_deg = 0.0;
  EXPECT_EQ(ValidationErrorKey(c), "social_force.fov_deg");
}

}  // namespace
}  // namespace retrace::sim
