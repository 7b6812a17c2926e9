#include "sim/teacher.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "tests/support/config_key.hpp"

namespace retrace::sim {
namespace {

using core::Pose2;
using core::Vec2;
using retrace::testing::kValid;
using retrace::testing::ValidationErrorKey;

constexpr double kDt = 0.05;  // control period (s)

// Exact unicycle step (a circular arc); no physics.
Pose2 Step(const Pose2& X, const core::Twist& u, double dt) {
  const double dth = u.omega * dt;
  const double h = 0.5 * dth;
  const double chord = u.v * dt * (std::abs(h) < 1e-9 ? 1.0 : std::sin(h) / h);
  return {X.x + chord * std::cos(X.theta + h), X.y + chord * std::sin(X.theta + h), X.theta + dth};
}

double DistanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// Distance from p to the part of the route with arc length in [s0, s1].
double DistanceToRoutePart(const std::vector<Vec2>& route, const Vec2& p, double s0, double s1) {
  double best = std::numeric_limits<double>::infinity();
  double arc = 0.0;
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    const double len = (route[i + 1] - route[i]).norm();
    const double a = std::max(s0, arc), b = std::min(s1, arc + len);
    if (a <= b) {
      const Vec2 d = (route[i + 1] - route[i]) / len;
      best =
          std::min(best, DistanceToSegment(p, route[i] + (a - arc) * d, route[i] + (b - arc) * d));
    }
    arc += len;
  }
  return best;
}

double Length(const std::vector<Vec2>& route) {
  double l = 0.0;
  for (std::size_t i = 0; i + 1 < route.size(); ++i) l += (route[i + 1] - route[i]).norm();
  return l;
}

struct Tick {
  Pose2 X_WR;
  core::Twist u;
  double progress;
  double wobble;
};

struct DriveLog {
  std::vector<Tick> ticks;
  bool done = false;
  double driven = 0.0;      // path length of the robot (m)
  double max_local = 0.0;   // largest distance to the route near the progress point (m)
  double max_global = 0.0;  // largest distance to the whole route (m)
  bool progress_monotone = true;
  double final_progress = 0.0;
  Pose2 final_pose;
};

DriveLog DriveRoute(const std::vector<Vec2>& route, const TeacherConfig& config, std::uint64_t seed,
                    double max_time = 600.0) {
  Teacher teacher(route, config, core::Rng(seed).Split("teacher"));
  const Vec2 d0 = route[1] - route[0];
  Pose2 X_WR(route[0].x(), route[0].y(), std::atan2(d0.y(), d0.x()));
  DriveLog drive;
  double last_progress = 0.0;
  for (double t = 0.0; t < max_time && !teacher.Done(); t += kDt) {
    const core::Twist u = teacher.Command(X_WR, kDt);
    drive.ticks.push_back({X_WR, u, teacher.Progress(), teacher.wobble()});
    if (teacher.Progress() < last_progress) drive.progress_monotone = false;
    last_progress = teacher.Progress();
    const double s = teacher.Progress();
    drive.max_local =
        std::max(drive.max_local, DistanceToRoutePart(route, X_WR.translation(), s - 2.0, s + 2.0));
    drive.max_global = std::max(drive.max_global,
                                DistanceToRoutePart(route, X_WR.translation(), 0.0, Length(route)));
    const Pose2 next = Step(X_WR, u, kDt);
    drive.driven += Distance(X_WR, next);
    X_WR = next;
  }
  drive.done = teacher.Done();
  drive.final_progress = teacher.Progress();
  drive.final_pose = X_WR;
  return drive;
}

const std::vector<Vec2> kLRoute{{0.0, 0.0}, {20.0, 0.0}, {20.0, 15.0}};

TEST(Teacher, RouteLengthIsTheArcLength) {
  const Teacher teacher(kLRoute, TeacherConfig{}, core::Rng(1));
  EXPECT_DOUBLE_EQ(teacher.RouteLength(), 35.0);
  EXPECT_EQ(teacher.Progress(), 0.0);
  EXPECT_FALSE(teacher.Done());
}

TEST(Teacher, FollowsLShapedRouteAndStopsAtTheEnd) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const DriveLog d = DriveRoute(kLRoute, TeacherConfig{}, seed);
    EXPECT_TRUE(d.done) << "seed " << seed;
    EXPECT_LT(d.max_global, 0.3) << "seed " << seed;
    EXPECT_LE((d.final_pose.translation() - kLRoute.back()).norm(),
              TeacherConfig{}.goal_tolerance + 0.05);
    EXPECT_NEAR(d.driven, 35.0, 1.0);
    EXPECT_TRUE(d.progress_monotone);
    EXPECT_GT(d.final_progress, 34.0);
  }
}

TEST(Teacher, CommandsNothingOnceDone) {
  Teacher teacher({{0.0, 0.0}, {3.0, 0.0}}, TeacherConfig{}, core::Rng(1));
  Pose2 X;
  for (int k = 0; k < 2000 && !teacher.Done(); ++k) X = Step(X, teacher.Command(X, kDt), kDt);
  ASSERT_TRUE(teacher.Done());
  EXPECT_EQ(teacher.Command(X, kDt), core::Twist{});
  EXPECT_EQ(teacher.Command(Pose2(-5.0, 0.0, 0.0), kDt), core::Twist{});
  EXPECT_TRUE(teacher.Done());
}

TEST(Teacher, SlowsDownInTurns) {
  const TeacherConfig config;
  const DriveLog d = DriveRoute(kLRoute, config, 7);
  double straight_sum = 0.0, turn_max = 0.0;
  int straight_n = 0;
  for (const Tick& t : d.ticks) {
    if (t.progress > 6.0 && t.progress < 15.0) {
      straight_sum += t.u.v;
      ++straight_n;
    }
    if (t.progress > 19.5 && t.progress < 20.5) turn_max = std::max(turn_max, t.u.v);
  }
  ASSERT_GT(straight_n, 0);
  const double straight = straight_sum / straight_n;
  EXPECT_NEAR(straight, config.speed, 0.02);
  EXPECT_GT(turn_max, 0.0);
  EXPECT_LT(turn_max, 0.6 * straight);
  for (const Tick& t : d.ticks) {
    EXPECT_LE(t.u.v, config.speed + 1e-12);
    EXPECT_GE(t.u.v, 0.0);
    EXPECT_LE(std::abs(t.u.omega), config.max_yaw_rate + 1e-12);
  }
}

TEST(Teacher, WobbleIsBoundedAndNonzero) {
  const std::vector<Vec2> straight{{0.0, 0.0}, {300.0, 0.0}};
  const TeacherConfig config;
  double sum2 = 0.0, max_abs = 0.0, max_wobble = 0.0;
  int n = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const DriveLog d = DriveRoute(straight, config, seed);
    ASSERT_TRUE(d.done);
    for (const Tick& t : d.ticks) {
      max_wobble = std::max(max_wobble, std::abs(t.wobble));
      if (t.X_WR.x < 5.0 || t.X_WR.x > 295.0) continue;
      sum2 += t.X_WR.y * t.X_WR.y;
      max_abs = std::max(max_abs, std::abs(t.X_WR.y));
      ++n;
    }
  }
  const double rms = std::sqrt(sum2 / n);
  // The robot's lateral offset follows the OU offset of the target, smoothed by pure pursuit.
  EXPECT_GT(rms, 0.4 * config.wobble_amplitude);
  EXPECT_LT(rms, 1.5 * config.wobble_amplitude);
  EXPECT_LE(max_wobble, 3.0 * config.wobble_amplitude + 1e-12);
  EXPECT_LT(max_abs, 3.5 * config.wobble_amplitude);

  TeacherConfig still = config;
  still.wobble_amplitude = 0.0;
  const DriveLog d = DriveRoute(straight, still, 1);
  double max_y = 0.0;
  for (const Tick& t : d.ticks) max_y = std::max(max_y, std::abs(t.X_WR.y));
  EXPECT_LT(max_y, 1e-9);
}

// Routes that cross or revisit themselves must be followed in order, to the end.
struct RevisitCase {
  std::string name;
  std::vector<Vec2> route;
};

class TeacherRevisit : public ::testing::TestWithParam<RevisitCase> {};

TEST_P(TeacherRevisit, FollowsTheRouteInOrder) {
  const std::vector<Vec2>& route = GetParam().route;
  const double length = Length(route);
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const DriveLog d = DriveRoute(route, TeacherConfig{}, seed);
    EXPECT_TRUE(d.done) << "seed " << seed;
    EXPECT_TRUE(d.progress_monotone);
    EXPECT_GT(d.final_progress, length - 1.5);
    // Close to the part of the route it is on, not merely to some part of it.
    EXPECT_LT(d.max_local, 0.3) << "seed " << seed;
    // Drove the whole route: no shortcut to a later, nearby part.
    EXPECT_NEAR(d.driven, length, 0.05 * length) << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(
    TeacherRoutes, TeacherRevisit,
    ::testing::Values(
        // Two laps of a square: ends where it starts, passes the start half way.
        RevisitCase{
            "TwoLaps",
            {{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}}},
        // A figure eight crossing itself in the middle.
        RevisitCase{"FigureEight", {{0, 0}, {10, 8}, {10, 0}, {0, 8}, {0, 0}}},
        // Out along a corridor and back on the same line, then off to the side.
        RevisitCase{"OutAndBack", {{0, 0}, {12, 0}, {0, 0}, {0, 8}}},
        // A hairpin whose legs are 1.5 m apart.
        RevisitCase{"Hairpin", {{0, 0}, {15, 0}, {15, 1.5}, {0, 1.5}}}),
    [](const ::testing::TestParamInfo<RevisitCase>& param) { return param.param.name; });

TEST(Teacher, TurnsOnTheSpotWhenStartingBackwards) {
  Teacher teacher(kLRoute, TeacherConfig{}, core::Rng(2));
  Pose2 X(0.0, 0.0, core::kPi);
  const core::Twist first = teacher.Command(X, kDt);
  EXPECT_EQ(first.v, 0.0);
  EXPECT_NE(first.omega, 0.0);
  double max_dist = 0.0;
  for (int k = 0; k < 4000 && !teacher.Done(); ++k) {
    X = Step(X, teacher.Command(X, kDt), kDt);
    max_dist = std::max(max_dist, DistanceToRoutePart(kLRoute, X.translation(), 0.0, 35.0));
  }
  EXPECT_TRUE(teacher.Done());
  EXPECT_LT(max_dist, 0.3);
}

TEST(Teacher, LoopRouteIsNotDoneAtItsStart) {
  const std::vector<Vec2> loop{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}};
  Teacher teacher(loop, TeacherConfig{}, core::Rng(1));
  const core::Twist u = teacher.Command(Pose2(0.0, 0.0, 0.0), kDt);
  EXPECT_FALSE(teacher.Done());
  EXPECT_GT(u.v, 0.0);
}

TEST(Teacher, TurnsBackAtACrossingItComesToAgainAndDrivesTheWholeRoute) {
  // Out to (10, 0) and back, round a block, and out to (10, 0) again to turn back there: both
  // U-turns are stops at the same place. The first must not be taken for the second (before, the
  // progress jumped from 10 m to 45 m and the drive skipped the block).
  const std::vector<Vec2> route{{0, 0}, {10, 0}, {0, 0}, {0, 5}, {10, 5}, {10, 0}, {10, 5}};
  const DriveLog d = DriveRoute(route, TeacherConfig{}, 3);
  EXPECT_TRUE(d.done);
  EXPECT_TRUE(d.progress_monotone);
  EXPECT_NEAR(d.driven, Length(route), 1.5);
  for (std::size_t i = 1; i < d.ticks.size(); ++i) {
    ASSERT_LT(d.ticks[i].progress - d.ticks[i - 1].progress, 1.0) << "a jump at tick " << i;
  }
}

TEST(Teacher, IsDeterministicPerSeed) {
  const DriveLog a = DriveRoute(kLRoute, TeacherConfig{}, 3);
  const DriveLog b = DriveRoute(kLRoute, TeacherConfig{}, 3);
  const DriveLog c = DriveRoute(kLRoute, TeacherConfig{}, 4);
  ASSERT_EQ(a.ticks.size(), b.ticks.size());
  EXPECT_EQ(a.final_pose, b.final_pose);
  EXPECT_NE(a.final_pose, c.final_pose);
}

std::string RouteErrorKey(const std::vector<Vec2>& route) {
  try {
    ValidateRoute(route);
  } catch (const core::ConfigError& e) {
    return e.key_path();
  }
  return "";
}

TEST(Teacher, ValidateRouteRejectsBadRoutes) {
  EXPECT_EQ(RouteErrorKey(kLRoute), "");
  EXPECT_EQ(RouteErrorKey({}), "route");
  EXPECT_EQ(RouteErrorKey({{1.0, 2.0}}), "route");
  EXPECT_EQ(RouteErrorKey({{0, 0}, {1, 0}, {1, 0}}), "route[2]");
  EXPECT_EQ(RouteErrorKey({{0, 0}, {std::nan(""), 0}}), "route[1]");
  EXPECT_EQ(RouteErrorKey({{0, 0}, {1, std::numeric_limits<double>::infinity()}}), "route[1]");
  EXPECT_THROW(Teacher({{0, 0}}, TeacherConfig{}, core::Rng(1)), core::ConfigError);
}

TEST(TeacherConfig, ValidateNamesTheKey) {
  EXPECT_EQ(ValidationErrorKey(TeacherConfig{}), kValid);
  TeacherConfig c;
  c.speed = 0.0;
  EXPECT_EQ(ValidationErrorKey(c), "speed");
  c = {};
  c.min_turn_speed = 2.0;
  EXPECT_EQ(ValidationErrorKey(c), "min_turn_speed");
  c = {};
  c.lookahead = -1.0;
  EXPECT_EQ(ValidationErrorKey(c), "lookahead");
  c = {};
  c.wobble_amplitude = 1.0;
  EXPECT_EQ(ValidationErrorKey(c), "wobble_amplitude");
  c = {};
  c.wobble_time_constant = 0.0;
  EXPECT_EQ(ValidationErrorKey(c), "wobble_time_constant");
  c = {};
  c.goal_tolerance = std::nan("");
  EXPECT_EQ(ValidationErrorKey(c), "goal_tolerance");
  c = {};
  c.max_yaw_rate = 0.0;
  EXPECT_EQ(ValidationErrorKey(c), "max_yaw_rate");
  c = {};
  c.speed = -1.0;
  EXPECT_THROW(Teacher(kLRoute, c, core::Rng(1)), core::ConfigError);
}

}  // namespace
}  // namespace retrace::sim
