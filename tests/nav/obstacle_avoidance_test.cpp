#include "nav/obstacle_avoidance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/path.hpp"
#include "nav/path_follower.hpp"
#include "tests/support/config_key.hpp"
#include "tests/support/fake_scan.hpp"
#include "tests/support/special_values.hpp"

namespace retrace::nav {
namespace {

using core::Pose2;
using core::Vec2;
using retrace::testing::kValid;
using retrace::testing::ValidationErrorKey;

using retrace::testing::kInf;
constexpr double kDt = 0.05;  // s, control period

using testing::Segment;

std::vector<Segment> Box(double x0, double y0, double x1, double y1) {
  return {{{x0, y0}, {x1, y0}}, {{x1, y0}, {x1, y1}}, {{x1, y1}, {x0, y1}}, {{x0, y1}, {x0, y0}}};
}

void Append(std::vector<Segment>& to, const std::vector<Segment>& more) {
  to.insert(to.end(), more.begin(), more.end());
}

using ScanGeometry = testing::ScanSpec;

// Exact ray casting of every beam of a LiDAR at X_WL against `segments` (in W): REP-117
// readings (+inf no return, -inf closer than range_min).
core::LaserScan CastScan(const std::vector<Segment>& segments, const Pose2& X_WL,
                         const ScanGeometry& g = {}) {
  return testing::FakeScan(g, X_WL, [&](const Vec2& o, const Vec2& d) {
    return testing::NearestSegment(o, d, segments);
  });
}

double DistanceToSegment(const Vec2& p, const Segment& s) {
  const Vec2 e = s.b - s.a;
  const double t = std::clamp((p - s.a).dot(e) / e.squaredNorm(), 0.0, 1.0);
  return (p - (s.a + t * e)).norm();
}

double Clearance(const Vec2& p, const std::vector<Segment>& segments, double radius) {
  double best = kInf;
  for (const Segment& s : segments) best = std::min(best, DistanceToSegment(p, s));
  return best - radius;
}

// A differential-drive robot with the simulator's default limits (1 m/s², 3 rad/s²), stepped
// kinematically at 100 Hz, commanded at 20 Hz.
struct Robot {
  Pose2 X_WR;
  core::Twist setpoint;
  void Step(const core::Twist& command) {
    for (int k = 0; k < 5; ++k) {
      const double h = kDt / 5.0;
      setpoint.v += std::clamp(command.v - setpoint.v, -1.0 * h, 1.0 * h);
      setpoint.omega += std::clamp(command.omega - setpoint.omega, -3.0 * h, 3.0 * h);
      X_WR = core::IntegrateOdometry(X_WR, {setpoint.v * h, setpoint.omega * h});
    }
  }
};

struct Rollout {
  double min_clearance = kInf;  // m, footprint (radius 0.3) to the nearest segment
  bool any_blocked = false;
  bool any_emergency = false;
  bool any_modified = false;
  Robot robot;
  std::vector<AvoidanceOutput> outputs;
};

Rollout Roll(ObstacleAvoidance& avoidance, const std::vector<Segment>& world, Pose2 start,
             double seconds, const std::function<core::Twist(const Pose2&, bool*)>& desired_of) {
  Rollout r;
  r.robot.X_WR = start;
  for (double t = 0.0; t < seconds; t += kDt) {
    bool done = false;
    const core::Twist desired = desired_of(r.robot.X_WR, &done);
    if (done) break;
    const core::LaserScan scan = CastScan(world, r.robot.X_WR * avoidance.robot().X_RL);
    const AvoidanceOutput out = avoidance.Filter(desired, scan);
    r.outputs.push_back(out);
    r.any_blocked |= out.blocked;
    r.any_emergency |= out.emergency_stop;
    r.any_modified |= out.modified;
    r.robot.Step(out.command);
    r.min_clearance = std::min(r.min_clearance, Clearance(r.robot.X_WR.translation(), world, 0.3));
  }
  return r;
}

TEST(ObstacleAvoidance, DistanceToContactMatchesBruteForce) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> coord(-3.0, 3.0);
  std::uniform_real_distribution<double> curv(-2.0, 2.0);
  const double r = 0.4;
  const double max_distance = 4.0;
  const double h = 5e-4;
  int compared = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const Vec2 p(coord(gen), coord(gen));
    const double kappa = trial % 5 == 0 ? 0.0 : curv(gen);
    auto centre = [&](double s) -> Vec2 {
      if (kappa == 0.0) return {s, 0.0};
      return {std::sin(kappa * s) / kappa, (1.0 - std::cos(kappa * s)) / kappa};
    };
    // Skip grazing cases that a sampled reference cannot decide.
    if (std::abs(p.norm() - r) < 0.01) continue;
    double min_gap = kInf;
    for (double s = 0.0; s <= max_distance; s += h) {
      min_gap = std::min(min_gap, std::abs((centre(s) - p).norm() - r));
    }
    if (min_gap < 0.01) continue;
    double expected = kInf;
    bool was_inside = p.norm() < r;
    if (was_inside && p.x() > 0.0) {
      expected = 0.0;
    } else {
      for (double s = h; s <= max_distance; s += h) {
        const bool inside = (centre(s) - p).norm() < r;
        if (inside && !was_inside) {
          expected = s;
          break;
        }
        was_inside = inside;
      }
    }
    const double got = DistanceToContact(kappa, r, max_distance, p);
    if (std::isinf(expected)) {
      EXPECT_TRUE(std::isinf(got)) << "p=" << p.transpose() << " kappa=" << kappa << " got " << got;
    } else {
      EXPECT_NEAR(got, expected, 2.0 * h) << "p=" << p.transpose() << " kappa=" << kappa;
    }
    ++compared;
  }
  EXPECT_GT(compared, 300);
}

TEST(ObstacleAvoidance, ReportsTimeToCollisionWithAWallAhead) {
  ObstacleAvoidance avoidance({}, RobotGeometry{});
  const std::vector<Segment> wall = {{{1.9, -5.0}, {1.9, 5.0}}};
  const AvoidanceOutput out = avoidance.Filter({1.0, 0.0}, CastScan(wall, Pose2()));
  // Footprint radius + margin 0.4 m touches the wall after 1.5 m at 1 m/s.
  EXPECT_NEAR(out.time_to_collision, 1.5, 1e-6);
  EXPECT_TRUE(out.modified);
}

TEST(ObstacleAvoidance, StopsBeforeADeadEnd) {
  // A corridor 2 m wide closed by a wall at x = 5; the desired command drives straight on.
  std::vector<Segment> world = {
      {{-1.0, -1.0}, {5.0, -1.0}}, {{-1.0, 1.0}, {5.0, 1.0}}, {{5.0, -1.0}, {5.0, 1.0}}};
  ObstacleAvoidance avoidance({}, RobotGeometry{});
  const Rollout r = Roll(avoidance, world, Pose2(), 15.0, [](const Pose2&, bool*) {
    return core::Twist{1.0, 0.0};
  });
  EXPECT_TRUE(r.any_blocked || r.any_emergency);
  EXPECT_GT(r.min_clearance, 0.0);  // the footprint never touched anything
  EXPECT_NEAR(r.robot.setpoint.v, 0.0, 1e-12);
  EXPECT_EQ(r.outputs.back().command.v, 0.0);
  const double gap = 5.0 - r.robot.X_WR.x - 0.3;
  EXPECT_GT(gap, 0.0);
  RecordProperty("dead_end_gap", std::to_string(gap));
  RecordProperty("dead_end_min_clearance", std::to_string(r.min_clearance));
}

TEST(ObstacleAvoidance, StopsForAClosedDoorAcrossThePathOfAFollower) {
  // The follower insists on a straight 10 m path along a 3 m wide corridor closed at x = 6.
  const std::vector<Segment> world = {
      {{6.0, -1.5}, {6.0, 1.5}}, {{-1.0, -1.5}, {6.0, -1.5}}, {{-1.0, 1.5}, {6.0, 1.5}}};
  PathFollower follower({});
  follower.SetPath(core::Path({Pose2(0, 0, 0), Pose2(5, 0, 0), Pose2(10, 0, 0)}));
  ObstacleAvoidance avoidance({}, RobotGeometry{});
  const Rollout r = Roll(avoidance, world, Pose2(), 20.0, [&](const Pose2& X, bool* done) {
    const FollowerOutput f = follower.Compute(X, kDt);
    *done = f.goal_reached;
    return f.command;
  });
  EXPECT_GT(r.min_clearance, 0.0);
  EXPECT_TRUE(r.any_blocked || r.any_emergency);
  EXPECT_NEAR(r.robot.setpoint.v, 0.0, 1e-12);
  EXPECT_LT(r.robot.X_WR.x, 6.0 - 0.3);
  RecordProperty("wall_gap", std::to_string(6.0 - r.robot.X_WR.x - 0.3));
}

TEST(ObstacleAvoidance, SteersPastABoxPartlyBlockingThePath) {
  // A box across the taught path's centre line; there is room on its right.
  const std::vector<Segment> world = Box(6.0, -0.3, 6.6, 0.5);
  PathFollower follower({});
  follower.SetPath(core::Path({Pose2(0, 0, 0), Pose2(8, 0, 0), Pose2(16, 0, 0)}));
  ObstacleAvoidance avoidance({}, RobotGeometry{});
  double max_deviation = 0.0;
  double final_error = kInf;
  bool reached = false;
  const Rollout r = Roll(avoidance, world, Pose2(), 40.0, [&](const Pose2& X, bool* done) {
    const FollowerOutput f = follower.Compute(X, kDt);
    max_deviation = std::max(max_deviation, std::abs(X.y));
    if (X.x > 13.0) final_error = std::abs(X.y);
    reached = *done = f.goal_reached;
    return f.command;
  });
  EXPECT_TRUE(reached);  // it went on to the end of the path
  EXPECT_TRUE(r.any_modified);
  EXPECT_FALSE(r.any_emergency);
  EXPECT_GT(r.min_clearance, 0.0);  // passed without touching
  EXPECT_GT(max_deviation, 0.6);    // it really went round (the box reaches y = -0.3)
  EXPECT_LT(final_error, 0.05);     // and came back onto the path
  for (const AvoidanceOutput& out : r.outputs) EXPECT_GE(out.command.v, 0.0);
  RecordProperty("box_min_clearance", std::to_string(r.min_clearance));
  RecordProperty("box_max_deviation", std::to_string(max_deviation));
}

TEST(ObstacleAvoidance, DrivesOnPastABinBesideItWhenOnlyTheMarginIsViolated) {
  // The campus deadlock: a bin on the taught path, the robot already beside its corner (0.42 m
  // from the centre, just outside the margin) while the follower pulls back towards the path
  // behind the bin. No arc keeps the 0.1 m margin, but the bare footprint passes: the robot
  // must drive on past the bin, not stop there for good.
  const std::vector<Segment> world = Box(0.29, -1.11, 1.09, -0.31);
  PathFollower follower({});
  follower.SetPath(core::Path({Pose2(-2.0, -0.71, 0), Pose2(1.0, -0.71, 0), Pose2(5.0, -0.71, 0)}));
  ObstacleAvoidance avoidance({}, RobotGeometry{});
  bool reached = false;
  const Rollout r =
      Roll(avoidance, world, Pose2(0.0, 0.0, 0.0), 30.0, [&](const Pose2& X, bool* done) {
        const FollowerOutput f = follower.Compute(X, kDt);
        reached = *done = f.goal_reached;
        return f.command;
      });
  EXPECT_TRUE(reached);
  EXPECT_GT(r.min_clearance, 0.0);  // the footprint never touched the bin
  RecordProperty("bin_min_clearance", std::to_string(r.min_clearance));
}

TEST(ObstacleAvoidance, ChosenCommandIsFreeWithinLimitsAndSlowsDown) {
  ObstacleAvoidance avoidance({}, RobotGeometry{});
  const std::vector<Segment> world = Box(1.5, -0.3, 2.0, 0.3);
  const AvoidanceOutput out = avoidance.Filter({1.0, 0.1}, CastScan(world, Pose2()));
  ASSERT_TRUE(out.modified);
  ASSERT_FALSE(out.blocked);
  EXPECT_LE(std::abs(out.command.omega), avoidance.config().max_yaw_rate + 1e-9);
  EXPECT_TRUE(out.command.v == 0.8 || out.command.v == 0.5) << out.command.v;
  // The chosen arc is free; the desired one was not.
  EXPECT_TRUE(std::isfinite(out.time_to_collision));
  const AvoidanceOutput again = avoidance.Filter(out.command, CastScan(world, Pose2()));
  EXPECT_FALSE(again.modified);
}

TEST(ObstacleAvoidance, PointsBehindAndBesideNeverTriggerTheEmergencyStop) {
  // Full 360-degree scan: a wall right behind the robot and walls 0.5 m on both sides.
  std::vector<Segment> world = {{{-0.35, -1.0}, {-0.35, 1.0}}};
  Append(world, {{{-1.0, -0.5}, {4.0, -0.5}}, {{-1.0, 0.5}, {4.0, 0.5}}});
  ScanGeometry full;
  full.fov = 2.0 * core::kPi;
  full.beams = 1440;
  ObstacleAvoidance avoidance({}, RobotGeometry{});
  const core::Twist desired{1.0, 0.0};
  const AvoidanceOutput out = avoidance.Filter(desired, CastScan(world, Pose2(), full));
  EXPECT_FALSE(out.emergency_stop);
  EXPECT_FALSE(out.blocked);
  EXPECT_FALSE(out.modified);
  EXPECT_EQ(out.command, desired);
}

TEST(ObstacleAvoidance, EmergencyStopForSomethingJustAhead) {
  ObstacleAvoidance avoidance({}, RobotGeometry{});
  const AvoidanceOutput out =
      avoidance.Filter({0.5, 0.2}, CastScan(Box(0.33, -0.05, 0.43, 0.05), Pose2()));
  EXPECT_TRUE(out.emergency_stop);
  EXPECT_EQ(out.command.v, 0.0);
  EXPECT_EQ(out.command.omega, 0.2);      // turning in place is still allowed
  EXPECT_LT(out.time_to_collision, 0.1);  // the bare footprint is 0.03 m from it
}

TEST(ObstacleAvoidance, NegativeInfinityReadingsAreCloseObstacles) {
  core::LaserScan scan = CastScan({}, Pose2());
  ASSERT_TRUE(std::isinf(scan.ranges[540]) && scan.ranges[540] > 0);
  for (std::size_t i = 520; i <= 560; ++i) scan.ranges[i] = -std::numeric_limits<float>::infinity();
  ObstacleAvoidance avoidance({}, RobotGeometry{});
  const AvoidanceOutput out = avoidance.Filter({1.0, 0.0}, scan);
  EXPECT_TRUE(out.emergency_stop);
  EXPECT_EQ(out.command.v, 0.0);
  // Same answer as a reading at range_min; NaN readings are ignored.
  for (std::size_t i = 520; i <= 560; ++i) scan.ranges[i] = static_cast<float>(scan.range_min);
  EXPECT_TRUE(avoidance.Filter({1.0, 0.0}, scan).emergency_stop);
  for (std::size_t i = 520; i <= 560; ++i) scan.ranges[i] = std::nanf("");
  EXPECT_FALSE(avoidance.Filter({1.0, 0.0}, scan).modified);
}

TEST(ObstacleAvoidance, AppliesTheLidarMount) {
  // A LiDAR mounted 0.1 m ahead of the centre, looking backwards.
  RobotGeometry robot;
  robot.X_RL = Pose2(0.1, 0.0, core::kPi);
  ObstacleAvoidance avoidance({}, robot);
  ScanGeometry full;
  full.fov = 2.0 * core::kPi;
  full.beams = 720;
  // Something 0.2 m from the sensor along L's x axis lies behind the robot's centre.
  const Pose2 X_WL = robot.X_RL;
  const AvoidanceOutput behind =
      avoidance.Filter({1.0, 0.0}, CastScan(Box(-0.15, -0.05, -0.1, 0.05), X_WL, full));
  EXPECT_FALSE(behind.emergency_stop);
  const AvoidanceOutput ahead =
      avoidance.Filter({1.0, 0.0}, CastScan(Box(0.25, -0.05, 0.3, 0.05), X_WL, full));
  EXPECT_TRUE(ahead.emergency_stop);
}

TEST(ObstacleAvoidance, DisabledPassesTheCommandThrough) {
  ObstacleAvoidanceConfig config;
  config.enabled = false;
  ObstacleAvoidance avoidance(config, RobotGeometry{});
  const core::Twist desired{0.7, -0.3};
  const AvoidanceOutput out =
      avoidance.Filter(desired, CastScan({{{0.35, -2.0}, {0.35, 2.0}}}, Pose2()));
  EXPECT_EQ(out.command, desired);
  EXPECT_FALSE(out.modified || out.blocked || out.emergency_stop);
}

TEST(ObstacleAvoidance, TurningInPlaceIsPassedThrough) {
  ObstacleAvoidance avoidance({}, RobotGeometry{});
  const core::Twist desired{0.0, 0.5};
  const AvoidanceOutput out =
      avoidance.Filter(desired, CastScan({{{0.35, -2.0}, {0.35, 2.0}}}, Pose2()));
  EXPECT_EQ(out.command, desired);
  EXPECT_FALSE(out.modified);
}

TEST(ObstacleAvoidance, RejectsInvalidConfigNamingTheKey) {
  EXPECT_EQ(ValidationErrorKey<ObstacleAvoidanceConfig>([](auto&) {}), kValid);
  EXPECT_EQ(ValidationErrorKey<ObstacleAvoidanceConfig>([](auto& c) { c.omega_step = -0.1; }),
            "omega_step");
  EXPECT_EQ(ValidationErrorKey<ObstacleAvoidanceConfig>([](auto& c) { c.speed_factors = {}; }),
            "speed_factors");
  EXPECT_EQ(ValidationErrorKey<ObstacleAvoidanceConfig>([](auto& c) {
              c.speed_factors = {0.8, 1.5};
            }),
            "speed_factors[1]");
  EXPECT_EQ(ValidationErrorKey<ObstacleAvoidanceConfig>([](auto& c) { c.horizon = std::nan(""); }),
            "horizon");
  ObstacleAvoidanceConfig bad;
  bad.emergency_stop_width = 0.0;
  EXPECT_THROW(ObstacleAvoidance(bad, RobotGeometry{}), core::ConfigError);
  RobotGeometry bad_robot;
  bad_robot.radius = 0.0;
  EXPECT_THROW(ObstacleAvoidance({}, bad_robot), core::ConfigError);
}

}  // namespace
}  // namespace retrace::nav
