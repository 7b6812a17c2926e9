#include "sim/robot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/errors.hpp"
#include "sim/physics_world.hpp"
#include "tests/sim/add_box.hpp"
#include "tests/support/config_key.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::ValidationErrorKey;

using test_geometry::AddBox;

StaticGeometry FarAwayWall() {
  StaticGeometry g;
  AddBox(g, 100.0, -1.0, 101.0, 1.0);
  return g;
}

TEST(Robot, DefaultConfigIsValidAndBadValuesNameTheKey) {
  RobotConfig c;
  EXPECT_NO_THROW(c.Validate());
  c.max_accel = 0.0;
  EXPECT_EQ(ValidationErrorKey(c), "max_accel");
  c = {};
  c.max_reverse_speed = -0.1;
  EXPECT_THROW(c.Validate(), core::ConfigError);
  c = {};
  c.radius = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(c.Validate(), core::ConfigError);
}

TEST(Robot, SpawningInsideOrAcrossAWallIsAWorldError) {
  StaticGeometry g;
  AddBox(g, 0.0, 0.0, 2.0, 2.0);
  {
    PhysicsWorld world(g);
    EXPECT_THROW(Robot(RobotConfig{}, g, core::Pose2(1.0, 1.0, 0.0), world), core::WorldError);
  }
  {
    PhysicsWorld world(g);
    try {
      Robot robot(RobotConfig{}, g, core::Pose2(2.1, 1.0, 0.0), world);
      FAIL();
    } catch (const core::WorldError& e) {
      EXPECT_NE(std::string(e.what()).find("robot"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("overlaps"), std::string::npos) << e.what();
    }
  }
  PhysicsWorld world(g);
  EXPECT_NO_THROW(Robot(RobotConfig{}, g, core::Pose2(2.5, 1.0, 0.0), world));
}

TEST(Robot, ClampsCommandsToSpeedLimits) {
  const RobotConfig c;
  EXPECT_EQ(ClampToLimits({5.0, 9.0}, c), (core::Twist{1.0, 1.5}));
  EXPECT_EQ(ClampToLimits({-5.0, -9.0}, c), (core::Twist{-0.2, -1.5}));
  EXPECT_EQ(ClampToLimits({0.5, 0.1}, c), (core::Twist{0.5, 0.1}));
  EXPECT_EQ(ClampToLimits({std::nan(""), 0.1}, c), (core::Twist{0.0, 0.1}));
}

TEST(Robot, RespectsSpeedAndAccelerationLimitsInMotion) {
  const StaticGeometry g = FarAwayWall();
  PhysicsWorld world(g);
  const RobotConfig c;
  Robot robot(c, g, core::Pose2(0.0, 0.0, 0.0), world);
  const double dt = world.time_step();
  core::Twist prev_setpoint;
  core::Pose2 prev_pose = robot.Pose(world);
  double max_speed = 0.0, max_yaw_rate = 0.0;
  // Full ahead with a hard turn for 3 s, then full reverse for 3 s.
  for (int i = 0; i < 600; ++i) {
    robot.SetCommand(i < 300 ? core::Twist{5.0, 4.0} : core::Twist{-5.0, -4.0});
    robot.Actuate(world);
    world.Step();
    const core::Twist sp = robot.setpoint();
    EXPECT_LE(std::abs(sp.v - prev_setpoint.v), c.max_accel * dt + 1e-12);
    EXPECT_LE(std::abs(sp.omega - prev_setpoint.omega), c.max_yaw_accel * dt + 1e-12);
    EXPECT_LE(sp.v, c.max_speed);
    EXPECT_GE(sp.v, -c.max_reverse_speed);
    EXPECT_LE(std::abs(sp.omega), c.max_yaw_rate);
    const core::Pose2 pose = robot.Pose(world);
    const double speed = core::Distance(pose, prev_pose) / dt;
    const double yaw_rate = std::abs(core::AngleDiff(pose.theta, prev_pose.theta)) / dt;
    max_speed = std::max(max_speed, speed);
    max_yaw_rate = std::max(max_yaw_rate, yaw_rate);
    // Speed can only have grown at max_accel from rest.
    EXPECT_LE(speed, c.max_accel * world.time() + 1e-3);
    prev_setpoint = sp;
    prev_pose = pose;
  }
  EXPECT_NEAR(max_speed, c.max_speed, 1e-3);
  EXPECT_NEAR(max_yaw_rate, c.max_yaw_rate, 1e-3);
  EXPECT_NEAR(world.RobotTwist().v, -c.max_reverse_speed, 1e-4);
  EXPECT_NEAR(world.RobotTwist().omega, -c.max_yaw_rate, 1e-4);
}

TEST(Robot, AcceleratesFromRestAlongTheExpectedProfile) {
  const StaticGeometry g = FarAwayWall();
  PhysicsWorld world(g);
  Robot robot(RobotConfig{}, g, core::Pose2(0.0, 0.0, 0.0), world);
  robot.SetCommand({0.5, 0.0});
  for (int i = 0; i < 500; ++i) {
    robot.Actuate(world);
    world.Step();
  }
  // 0.5 s ramp at 1 m/s² covers 0.125 m, then 4.5 s at 0.5 m/s; the discrete ramp adds half a
  // step's worth (0.0025 m).
  EXPECT_NEAR(robot.Pose(world).x, 0.125 + 2.25, 0.005);
  EXPECT_NEAR(robot.Pose(world).y, 0.0, 1e-6);
}

TEST(Robot, BlockedByAWallStopsThereWhileTheSetpointStays) {
  StaticGeometry g;
  AddBox(g, 2.0, -3.0, 2.2, 8.0);
  PhysicsWorld world(g);
  const RobotConfig c;
  Robot robot(c, g, core::Pose2(0.0, 0.2, 0.3), world);
  robot.SetCommand({1.0, 0.0});
  double min_clearance = 1e9;
  int static_events = 0;
  for (int i = 0; i < 800; ++i) {
    robot.Actuate(world);
    world.Step();
    const double clearance = g.Clearance(robot.Pose(world).translation());
    min_clearance = std::min(min_clearance, clearance);
    ASSERT_GE(clearance, c.radius - 0.01) << "step " << i;
    for (const auto& e : world.TakeCollisions()) {
      EXPECT_EQ(e.kind, CollisionKind::kStatic);
      EXPECT_NEAR(e.point_W.x(), 2.0, 0.02);
      ++static_events;
    }
  }
  EXPECT_GE(static_events, 1);
  EXPECT_NEAR(robot.setpoint().v, 1.0, 1e-12);
  // Pushing at 0.3 rad into the wall, the forward component that remains is the slide.
  EXPECT_LT(world.RobotTwist().v, 0.5);
  EXPECT_NEAR(robot.Pose(world).x, 2.0 - c.radius, 0.02);
}

TEST(Robot, ResetTeleportsAndClearsTheSetpoint) {
  const StaticGeometry g = FarAwayWall();
  PhysicsWorld world(g);
  Robot robot(RobotConfig{}, g, core::Pose2(0.0, 0.0, 0.0), world);
  robot.SetCommand({1.0, 0.5});
  for (int i = 0; i < 100; ++i) {
    robot.Actuate(world);
    world.Step();
  }
  robot.Reset(g, core::Pose2(5.0, 1.0, 1.0), world);
  EXPECT_EQ(robot.setpoint(), core::Twist{});
  EXPECT_EQ(robot.command(), core::Twist{});
  robot.Actuate(world);
  world.Step();
  EXPECT_NEAR(robot.Pose(world).x, 5.0, 1e-5);
  EXPECT_NEAR(robot.Pose(world).theta, 1.0, 1e-5);
  EXPECT_THROW(robot.Reset(g, core::Pose2(100.5, 0.0, 0.0), world), core::WorldError);
}

}  // namespace
}  // namespace retrace::sim
