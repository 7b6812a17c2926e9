#include "sim/physics_world.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "sim/static_geometry.hpp"
#include "tests/sim/add_box.hpp"

namespace retrace::sim {
namespace {

using test_geometry::AddBox;

constexpr double kRadius = 0.3;

TEST(PhysicsWorld, RobotDrivingIntoWallStopsAtItAndRecordsOneStaticCollision) {
  StaticGeometry g;
  AddBox(g, 3.0, -5.0, 3.2, 5.0);
  PhysicsWorld world(g);
  world.AddRobot(core::Pose2(0.0, 0.0, 0.0), kRadius, 30.0);
  std::vector<CollisionEvent> events;
  double min_clearance = 1e9;
  for (int i = 0; i < 600; ++i) {
    world.SetRobotVelocity({1.0, 0.0});
    world.Step();
    const core::Vec2 p = world.RobotPose().translation();
    min_clearance = std::min(min_clearance, g.Clearance(p));
    ASSERT_GE(g.Clearance(p), kRadius - 0.01) << "step " << i;
    for (const auto& e : world.TakeCollisions()) events.push_back(e);
  }
  RecordProperty("min_clearance", std::to_string(min_clearance));
  const core::Pose2 X_WR = world.RobotPose();
  EXPECT_NEAR(X_WR.x, 3.0 - kRadius, 0.02);  // resting against the wall
  EXPECT_NEAR(X_WR.y, 0.0, 1e-4);
  EXPECT_NEAR(world.RobotTwist().v, 0.0, 0.02);  // blocked: the body does not move
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, CollisionKind::kStatic);
  EXPECT_EQ(events[0].pedestrian_id, -1);
  // Reaches the wall after (3 - 0.3) m at 1 m/s, give or take a step and Box2D's 1 cm skin.
  EXPECT_NEAR(events[0].time, 2.7, 0.03);
  EXPECT_NEAR(events[0].point_W.x(), 3.0, 0.02);
  EXPECT_NEAR(events[0].point_W.y(), 0.0, 0.02);
}

TEST(PhysicsWorld, OpenEdgesBlockFromBothSides) {
  StaticGeometry g;
  g.AddEdges({{{2.0, -3.0}, {2.0, 3.0}}}, OccupancyMask{});
  for (const double dir : {1.0, -1.0}) {
    PhysicsWorld world(g);
    const double start = dir > 0 ? 0.0 : 4.0;
    world.AddRobot(core::Pose2(start, 0.0, dir > 0 ? 0.0 : core::kPi), kRadius, 30.0);
    for (int i = 0; i < 400; ++i) {
      world.SetRobotVelocity({1.0, 0.0});
      world.Step();
      ASSERT_GE(std::abs(world.RobotPose().x - 2.0), kRadius - 0.01) << "dir " << dir;
    }
    EXPECT_NEAR(std::abs(world.RobotPose().x - 2.0), kRadius, 0.02);
    EXPECT_EQ(world.TakeCollisions().size(), 1u);
  }
}

TEST(PhysicsWorld, RobotSlidingAlongWallAtAnAngleNeverPenetrates) {
  StaticGeometry g;
  AddBox(g, -5.0, 1.0, 10.0, 1.2);
  g.AddCircle({{3.0, -1.0}, 0.4});
  PhysicsWorld world(g);
  world.AddRobot(core::Pose2(0.0, 0.0, 0.6), kRadius, 30.0);
  double min_clearance = 1e9;
  for (int i = 0; i < 800; ++i) {
    world.SetRobotVelocity({1.0, -0.1});
    world.Step();
    min_clearance = std::min(min_clearance, g.Clearance(world.RobotPose().translation()));
  }
  EXPECT_GE(min_clearance, kRadius - 0.01);
}

TEST(PhysicsWorld, RobotHittingPedestrianRecordsItsId) {
  StaticGeometry g;
  AddBox(g, 20.0, -5.0, 20.2, 5.0);  // far away
  PhysicsWorld world(g);
  world.AddRobot(core::Pose2(0.0, 0.0, 0.0), kRadius, 30.0);
  const int far = world.AddPedestrian({0.0, 5.0}, 0.3, 70.0);
  const int near = world.AddPedestrian({2.0, 0.05}, 0.3, 70.0);
  EXPECT_EQ(far, 0);
  EXPECT_EQ(near, 1);
  std::vector<CollisionEvent> events;
  for (int i = 0; i < 200; ++i) {
    world.SetRobotVelocity({1.0, 0.0});
    world.SetPedestrianVelocity(near, {0.0, 0.0});
    world.Step();
    const double d = (world.RobotPose().translation() - world.PedestrianPosition(near)).norm();
    ASSERT_GE(d, 0.6 - 0.01);
    for (const auto& e : world.TakeCollisions()) events.push_back(e);
  }
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events[0].kind, CollisionKind::kPedestrian);
  EXPECT_EQ(events[0].pedestrian_id, near);
  EXPECT_NEAR(events[0].time, 1.4, 0.03);
  EXPECT_NEAR(events[0].point_W.x(), 1.7, 0.03);
  for (const auto& e : events) EXPECT_EQ(e.pedestrian_id, near);
}

TEST(PhysicsWorld, PedestrianContactsWithEachOtherAreNotRobotCollisions) {
  StaticGeometry g;
  AddBox(g, -3.0, -3.0, -2.8, 3.0);
  PhysicsWorld world(g);
  world.AddRobot(core::Pose2(5.0, 5.0, 0.0), kRadius, 30.0);
  const int a = world.AddPedestrian({0.0, 0.0}, 0.3, 70.0);
  const int b = world.AddPedestrian({2.0, 0.0}, 0.3, 70.0);
  for (int i = 0; i < 300; ++i) {
    world.SetPedestrianVelocity(a, {1.0, 0.0});
    world.SetPedestrianVelocity(b, {-1.0, 0.0});
    world.Step();
    // Box2D has no continuous collision between two moving bodies: the step in which they meet
    // may overlap them by up to the closing speed times the time step (2 cm here) before the
    // contact pushes them apart again.
    ASSERT_GE((world.PedestrianPosition(a) - world.PedestrianPosition(b)).norm(), 0.6 - 0.025);
  }
  EXPECT_TRUE(world.TakeCollisions().empty());
}

TEST(PhysicsWorld, VelocitiesMoveBodiesAndTimeAdvancesInFixedSteps) {
  StaticGeometry g;
  g.AddCircle({{50.0, 50.0}, 1.0});
  PhysicsWorld world(g);
  world.AddRobot(core::Pose2(0.0, 0.0, core::kPi / 2), kRadius, 30.0);
  const int p = world.AddPedestrian({5.0, 0.0}, 0.25, 70.0);
  for (int i = 0; i < 100; ++i) {
    world.SetRobotVelocity({0.5, 0.2});
    world.SetPedestrianVelocity(p, {0.0, 1.3});
    world.Step();
  }
  EXPECT_EQ(world.step_count(), 100u);
  EXPECT_NEAR(world.time(), 1.0, 1e-12);
  EXPECT_NEAR(world.PedestrianPosition(p).y(), 1.3, 1e-4);
  EXPECT_NEAR(world.PedestrianVelocity(p).y(), 1.3, 1e-6);
  EXPECT_NEAR(world.RobotPose().theta, core::kPi / 2 + 0.2, 1e-4);
  EXPECT_NEAR(world.RobotTwist().v, 0.5, 1e-5);
  EXPECT_NEAR(world.RobotTwist().omega, 0.2, 1e-6);
  const auto circles = world.PedestrianCircles();
  ASSERT_EQ(circles.size(), 1u);
  EXPECT_EQ(circles[0].id, p);
  EXPECT_DOUBLE_EQ(circles[0].radius, 0.25);
  world.TeleportRobot(core::Pose2(1.0, 2.0, 0.0));
  EXPECT_NEAR(world.RobotPose().x, 1.0, 1e-6);
  EXPECT_NEAR(world.RobotTwist().v, 0.0, 1e-12);
}

TEST(PhysicsWorld, RejectsBadTimeStep) {
  StaticGeometry g;
  PhysicsConfig c;
  c.time_step = 0.0;
  try {
    PhysicsWorld world(g, c);
    FAIL() << "expected ConfigError";
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "time_step");
  }
  c = {};
  c.velocity_iterations = 0;
  EXPECT_THROW(PhysicsWorld(g, c), core::ConfigError);
}

TEST(PhysicsWorld, IsMovable) {
  StaticGeometry g;
  AddBox(g, 3.0, -5.0, 3.2, 5.0);
  PhysicsWorld a(g);
  a.AddRobot(core::Pose2(0.0, 0.0, 0.0), kRadius, 30.0);
  PhysicsWorld b(std::move(a));
  for (int i = 0; i < 400; ++i) {
    b.SetRobotVelocity({1.0, 0.0});
    b.Step();
  }
  EXPECT_EQ(b.TakeCollisions().size(), 1u);  // the contact listener moved along
}

}  // namespace
}  // namespace retrace::sim
