#include "sim/social_force.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "tests/support/config_key.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::ValidationErrorKey;

const SocialForceConfig kConfig;

TEST(SocialForce, GoalForceRelaxesToDesiredVelocityWithTimeConstantTau) {
  const Vec2 e(0.6, 0.8);
  const double v0 = 1.34;
  EXPECT_TRUE(GoalForce(Vec2::Zero(), e, v0, kConfig).isApprox(e * v0 / 0.5));
  // Integrating dv/dt = (v0 e - v)/tau from rest gives v(t) = v0 e (1 - exp(-t/tau)).
  Vec2 v = Vec2::Zero();
  const double dt = 1e-4;
  double t = 0.0;
  for (; t < kConfig.relaxation_time - 0.5 * dt; t += dt) {
    v = IntegrateVelocity(v, GoalForce(v, e, v0, kConfig), dt, 10.0);
  }
  EXPECT_NEAR(v.norm(), v0 * (1.0 - std::exp(-1.0)), 1e-3);
  EXPECT_NEAR(v.normalized().dot(e), 1.0, 1e-12);
  for (; t < 5.0; t += dt) v = IntegrateVelocity(v, GoalForce(v, e, v0, kConfig), dt, 10.0);
  EXPECT_NEAR(v.norm(), v0, 1e-4);
  // The desired velocity is a fixed point.
  EXPECT_NEAR(GoalForce(v0 * e, e, v0, kConfig).norm(), 0.0, 1e-12);
}

TEST(SocialForce, EllipseReducesToDistanceForAStandingPedestrian) {
  EXPECT_NEAR(EllipseSemiMinorAxis({3.0, 4.0}, Vec2::Zero()), 5.0, 1e-12);
  // Someone walking straight at me looks closer than they are.
  EXPECT_LT(EllipseSemiMinorAxis({3.0, 0.0}, {2.0, 0.0}), 3.0);
}

TEST(SocialForce, PedestrianRepulsionPointsAwayAndDecaysWithDistance) {
  const SocialAgent self{{0.0, 0.0}, {0.0, 0.0}, 0.3};
  double previous = std::numeric_limits<double>::infinity();
  for (const double d : {0.6, 0.8, 1.0, 1.5, 2.0, 3.0}) {
    const Vec2 dir = Vec2(1.0, 2.0).normalized();
    const SocialAgent other{d * dir, {0.0, 0.0}, 0.3};
    const Vec2 f = AgentRepulsion(self, other, 2.1, 0.3, kConfig);
    EXPECT_NEAR(f.normalized().dot(-dir), 1.0, 1e-12) << d;
    // V0/sigma exp(-(d - 2r)/sigma) for a standing neighbour.
    EXPECT_NEAR(f.norm(), 2.1 / 0.3 * std::exp(-(d - 0.6) / 0.3), 1e-9) << d;
    EXPECT_LT(f.norm(), previous);
    previous = f.norm();
  }
  const SocialAgent far{{6.0, 0.0}, {0.0, 0.0}, 0.3};
  EXPECT_EQ(AgentRepulsion(self, far, 2.1, 0.3, kConfig), Vec2::Zero());
}

TEST(SocialForce, SomeoneWalkingTowardsYouRepelsMoreThanSomeoneWalkingAway) {
  const SocialAgent self{{0.0, 0.0}, {0.0, 0.0}, 0.3};
  const SocialAgent towards{{2.0, 0.0}, {-1.3, 0.0}, 0.3};
  const SocialAgent away{{2.0, 0.0}, {1.3, 0.0}, 0.3};
  const SocialAgent standing{{2.0, 0.0}, {0.0, 0.0}, 0.3};
  const double f_towards = AgentRepulsion(self, towards, 2.1, 0.3, kConfig).norm();
  const double f_standing = AgentRepulsion(self, standing, 2.1, 0.3, kConfig).norm();
  const double f_away = AgentRepulsion(self, away, 2.1, 0.3, kConfig).norm();
  EXPECT_GT(f_towards, f_standing);
  EXPECT_GT(f_standing, f_away);
}

TEST(SocialForce, ObstacleRepulsionFollowsTheExponentialPotential) {
  double previous = std::numeric_limits<double>::infinity();
  for (const double d : {0.3, 0.5, 0.8, 1.2}) {
    const Vec2 f = ObstacleRepulsion({0.0, d}, {0.0, 0.0}, kConfig);
    EXPECT_NEAR(f.x(), 0.0, 1e-12);
    EXPECT_NEAR(f.y(), 10.0 / 0.2 * std::exp(-d / 0.2), 1e-9);
    EXPECT_LT(f.norm(), previous);
    previous = f.norm();
  }
  EXPECT_EQ(ObstacleRepulsion({0.0, 1.6}, {0.0, 0.0}, kConfig), Vec2::Zero());
}

TEST(SocialForce, FieldOfViewWeighsInteractionsBehindLess) {
  const Vec2 e(1.0, 0.0);
  // A force pushing me back comes from someone in front.
  EXPECT_EQ(FieldOfViewWeight(e, {-1.0, 0.0}, kConfig), 1.0);
  EXPECT_EQ(FieldOfViewWeight(e, {-0.1, 1.0}, kConfig), 1.0);  // source 84° off the heading: seen
  EXPECT_EQ(FieldOfViewWeight(e, {1.0, 0.0}, kConfig), 0.5);
  EXPECT_EQ(FieldOfViewWeight(e, {0.3, -1.0}, kConfig), 0.5);  // source 107° off: not seen
  EXPECT_EQ(FieldOfViewWeight(Vec2::Zero(), {1.0, 0.0}, kConfig), 1.0);
}

TEST(SocialForce, SelectObstaclePointsDropsDuplicatesAndHiddenPoints) {
  const Vec2 p(0.0, 0.0);
  std::vector<Vec2> pts = {
      {0.0, 0.7},   // far face of a thin wall behind the near face
      {0.0, 0.5},   // near face
      {0.5, 0.0},   // a perpendicular wall: kept
      {0.5, 0.0},   // the same corner from the neighbouring segment
      {0.1, 0.52},  // a staircase step next to the near face
  };
  SelectObstaclePoints(p, &pts);
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_EQ(pts[0], Vec2(0.0, 0.5));
  EXPECT_EQ(pts[1], Vec2(0.5, 0.0));
}

TEST(SocialForce, TotalForceIsCappedAndWallsAlwaysCount) {
  SocialForceInputs in;
  in.self = {{0.0, 0.0}, {0.0, 0.0}, 0.3};
  in.direction = {1.0, 0.0};
  in.desired_speed = 1.34;
  const std::vector<Vec2> wall = {{0.0, 0.31}};
  in.obstacle_points = wall;
  const Vec2 f = SocialForce(in, kConfig);
  EXPECT_NEAR(f.norm(), kConfig.max_acceleration, 1e-9);
  EXPECT_LT(f.y(), 0.0);
  // Behind the pedestrian, a wall still pushes at full strength.
  const std::vector<Vec2> wall_behind = {{-1.0, 0.0}};
  in.obstacle_points = wall_behind;
  const Vec2 g = SocialForce(in, kConfig);
  EXPECT_NEAR(g.x(), 1.34 / 0.5 + 10.0 / 0.2 * std::exp(-5.0), 1e-9);
}

TEST(SocialForce, ClearWalkingLineLetsDoorJambsSteerButNotBrake) {
  // Walking along +x towards a 1 m door whose jambs are 0.3 m ahead, 0.55 and 0.45 m aside.
  SocialForceInputs in;
  in.self = {{0.0, 0.0}, {0.5, 0.0}, 0.3};
  in.direction = {1.0, 0.0};
  in.desired_speed = 1.34;
  const std::vector<Vec2> jambs = {{0.3, 0.55}, {0.3, -0.45}};
  in.obstacle_points = jambs;
  const Vec2 blocked = SocialForce(in, kConfig);
  EXPECT_LT(blocked.x(), 0.0);  // the 1995 potential stops people in front of the door
  in.walking_line_clear = true;
  const Vec2 clear = SocialForce(in, kConfig);
  EXPECT_NEAR(clear.x(), GoalForce(in.self.velocity, in.direction, 1.34, kConfig).x(), 1e-9);
  EXPECT_NEAR(clear.y(), blocked.y(), 1e-9);  // still centred in the door
  EXPECT_GT(clear.y(), 0.0);
}

TEST(SocialForce, RobotRepulsionIsStrongerThanAPedestrians) {
  SocialForceInputs in;
  in.self = {{0.0, 0.0}, {1.0, 0.0}, 0.3};
  in.direction = {1.0, 0.0};
  in.desired_speed = 1.0;
  const SocialAgent ahead{{2.5, 0.3}, {0.0, 0.0}, 0.3};  // far enough not to hit the cap
  const std::vector<SocialAgent> others = {ahead};
  in.others = others;
  const Vec2 with_pedestrian = SocialForce(in, kConfig);
  in.others = {};
  in.robot = &ahead;
  const Vec2 with_robot = SocialForce(in, kConfig);
  ASSERT_LT(with_robot.norm(), kConfig.max_acceleration);
  EXPECT_LT(with_robot.x(), with_pedestrian.x());
  EXPECT_LT(with_robot.y(), with_pedestrian.y());
  EXPECT_LT(with_robot.y(), 0.0);  // steers away sideways
}

TEST(SocialForce, HeadOnPedestriansSidestepWithoutTouching) {
  // Two pedestrians on a collision course, 10 cm offset, integrated with the pure model.
  SocialAgent a{{0.0, 0.0}, {1.3, 0.0}, 0.3};
  SocialAgent b{{10.0, 0.1}, {-1.3, 0.0}, 0.3};
  const double dt = 0.01;
  double min_distance = 1e9;
  for (int i = 0; i < 1000; ++i) {
    SocialForceInputs ia, ib;
    ia.self = a;
    ia.direction = {1.0, 0.0};
    ia.desired_speed = 1.3;
    const std::vector<SocialAgent> oa = {b};
    ia.others = oa;
    ib.self = b;
    ib.direction = {-1.0, 0.0};
    ib.desired_speed = 1.3;
    const std::vector<SocialAgent> ob = {a};
    ib.others = ob;
    const Vec2 fa = SocialForce(ia, kConfig), fb = SocialForce(ib, kConfig);
    a.velocity = IntegrateVelocity(a.velocity, fa, dt, 1.3 * 1.3);
    b.velocity = IntegrateVelocity(b.velocity, fb, dt, 1.3 * 1.3);
    a.position += a.velocity * dt;
    b.position += b.velocity * dt;
    min_distance = std::min(min_distance, (a.position - b.position).norm());
  }
  EXPECT_GT(min_distance, 0.6);
  EXPECT_GT(a.position.x(), 10.0);  // both got past
  EXPECT_LT(b.position.x(), 0.0);
}

TEST(SocialForce, ValidateNamesTheKey) {
  SocialForceConfig c;
  EXPECT_NO_THROW(c.Validate());
  c.relaxation_time = 0.0;
  EXPECT_EQ(ValidationErrorKey(c), "relaxation_time");
  c = {};
  c.out_of_view_weight = 1.5;
  EXPECT_THROW(c.Validate(), core::ConfigError);
  c = {};
  c.max_speed_factor = 0.9;
  EXPECT_THROW(c.Validate(), core::ConfigError);
}

}  // namespace
}  // namespace retrace::sim
