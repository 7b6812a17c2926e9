#include "nav/path_follower.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/twist.hpp"
#include "tests/support/config_key.hpp"

namespace retrace::nav {
namespace {

using core::Pose2;
using core::Vec2;
using retrace::testing::kValid;
using retrace::testing::ValidationErrorKey;

constexpr double kPeriod = 0.05;  // s, the default 20 Hz control period

// Poses along a polyline through `points`, resampled every `step` m, headings along it.
core::Path Polyline(const std::vector<Vec2>& points, double step = 0.5) {
  std::vector<Vec2> dense;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const double len = (points[i + 1] - points[i]).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(len / step)));
    for (int k = 0; k < n; ++k)
      dense.push_back(points[i] + (points[i + 1] - points[i]) * (k / double(n)));
  }
  dense.push_back(points.back());
  core::Path path;
  for (std::size_t i = 0; i < dense.size(); ++i) {
    const Vec2 d = i + 1 < dense.size() ? dense[i + 1] - dense[i] : dense[i] - dense[i - 1];
    path.PushBack({dense[i].x(), dense[i].y(), std::atan2(d.y(), d.x())});
  }
  return path;
}

core::Path Straight(double length) { return Polyline({{0.0, 0.0}, {length, 0.0}}); }

// Points every `step` m of arc along a circle of radius r centred at (0, r) (starts at the
// origin heading +x, turns left), over `angle` rad.
std::vector<Vec2> ArcPoints(double r, double angle, Vec2 start = {0, 0}, double start_heading = 0,
                            bool left = true, double step = 0.5) {
  std::vector<Vec2> pts;
  const int n = std::max(1, static_cast<int>(std::ceil(r * angle / step)));
  const double sgn = left ? 1.0 : -1.0;
  for (int k = 0; k <= n; ++k) {
    const double a = angle * k / n;
    const Vec2 local(r * std::sin(a), sgn * r * (1.0 - std::cos(a)));
    const Pose2 X(start.x(), start.y(), start_heading);
    pts.push_back(X * local);
  }
  return pts;
}

struct Step {
  Pose2 pose;  // before the command
  FollowerOutput out;
};

// Simulates a kinematic unicycle that executes each command exactly for one period.
std::vector<Step> Drive(PathFollower& follower, Pose2 pose, double max_time) {
  std::vector<Step> log;
  for (double t = 0.0; t < max_time; t += kPeriod) {
    const FollowerOutput out = follower.Compute(pose, kPeriod);
    log.push_back({pose, out});
    if (out.goal_reached) break;
    pose = core::IntegrateOdometry(pose, {out.command.v * kPeriod, out.command.omega * kPeriod});
  }
  return log;
}

// Distance from p to the polyline of the path's positions.
double DistanceToPath(const core::Path& path, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const Vec2 a = path[i].translation();
    const Vec2 ab = path[i + 1].translation() - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (a + t * ab)).norm());
  }
  return best;
}

TEST(PathFollower, ConvergesOntoStraightPathFromLateralAndHeadingOffset) {
  PathFollower follower({});
  follower.SetPath(Straight(20.0));
  const auto log = Drive(follower, Pose2(0.0, 0.5, core::DegToRad(20.0)), 60.0);
  ASSERT_TRUE(log.back().out.goal_reached);
  double max_error_after_6m = 0.0;
  for (const Step& s : log) {
    if (s.pose.x > 6.0) max_error_after_6m = std::max(max_error_after_6m, std::abs(s.pose.y));
    EXPECT_GE(s.out.command.v, 0.0);
  }
  EXPECT_LT(max_error_after_6m, 0.05);
  RecordProperty("max_lateral_error_after_6m", std::to_string(max_error_after_6m));
}

TEST(PathFollower, ReportsSignedErrors) {
  PathFollower follower({});
  follower.SetPath(Straight(10.0));
  const FollowerOutput out = follower.Compute(Pose2(1.0, 0.3, 0.2), kPeriod);
  EXPECT_NEAR(out.lateral_error, 0.3, 1e-9);   // left of the path
  EXPECT_NEAR(out.heading_error, -0.2, 1e-9);  // must turn right
  EXPECT_LT(out.command.omega, 0.0);
}

TEST(PathFollower, TracksCircleArcWithBoundedError) {
  PathFollower follower({});
  std::vector<Vec2> pts = {{-2.0, 0.0}};
  for (const Vec2& p : ArcPoints(3.0, 1.5 * core::kPi)) pts.push_back(p);
  const core::Path path = Polyline(pts);
  follower.SetPath(path);
  const auto log = Drive(follower, Pose2(-2.0, 0.0, 0.0), 60.0);
  ASSERT_TRUE(log.back().out.goal_reached);
  double max_error = 0.0;
  double min_speed_on_arc = 1e9;
  for (const Step& s : log) {
    max_error = std::max(max_error, DistanceToPath(path, s.pose.translation()));
    if (s.pose.x > 0.5 && s.out.remaining > 2.0) {
      min_speed_on_arc = std::min(min_speed_on_arc, s.out.command.v);
    }
  }
  // Radius 3 m: curvature 0.33 1/m allows sqrt(0.5 / 0.33) = 1.22 m/s, so full speed.
  EXPECT_LT(max_error, 0.03);
  EXPECT_GT(min_speed_on_arc, 0.9);
  RecordProperty("max_error_on_arc", std::to_string(max_error));
}

TEST(PathFollower, TracksSCurveWithBoundedError) {
  std::vector<Vec2> pts = {{-2.0, 0.0}};
  for (const Vec2& p : ArcPoints(2.0, core::kPi / 2)) pts.push_back(p);
  const Vec2 mid = pts.back();
  const auto second = ArcPoints(2.0, core::kPi / 2, mid, core::kPi / 2, /*left=*/false);
  pts.insert(pts.end(), second.begin() + 1, second.end());
  pts.push_back(pts.back() + Vec2(3.0, 0.0));
  const core::Path path = Polyline(pts);
  PathFollower follower({});
  follower.SetPath(path);
  const auto log = Drive(follower, Pose2(-2.0, 0.0, 0.0), 60.0);
  ASSERT_TRUE(log.back().out.goal_reached);
  double max_error = 0.0;
  for (const Step& s : log)
    max_error = std::max(max_error, DistanceToPath(path, s.pose.translation()));
  EXPECT_LT(max_error, 0.05);
  RecordProperty("max_error_on_s_curve", std::to_string(max_error));
}

TEST(PathFollower, SlowsDownInTightCurves) {
  // 5 m straight, then a quarter circle of radius 1 m, then 5 m straight.
  std::vector<Vec2> pts = {{-5.0, 0.0}};
  for (const Vec2& p : ArcPoints(1.0, core::kPi / 2, {0, 0}, 0, true, 0.1)) pts.push_back(p);
  pts.push_back({1.0, 6.0});
  PathFollower follower({});
  follower.SetPath(Polyline(pts, 0.1));
  const auto log = Drive(follower, Pose2(-5.0, 0.0, 0.0), 60.0);
  ASSERT_TRUE(log.back().out.goal_reached);
  double max_straight = 0.0;
  double max_curve = 0.0;
  for (const Step& s : log) {
    if (s.pose.x < -3.5) max_straight = std::max(max_straight, s.out.command.v);
    if (s.pose.x > 0.3 && s.pose.y < 0.7) max_curve = std::max(max_curve, s.out.command.v);
  }
  EXPECT_GT(max_straight, 0.95);
  EXPECT_LT(max_curve, std::sqrt(0.5 / 1.0) + 0.05);  // sqrt(a_lat / kappa)
}

TEST(PathFollower, StopsAtTheEndOfThePathWithinTolerance) {
  PathFollowerConfig config;
  PathFollower follower(config);
  const core::Path path = Straight(10.0);
  follower.SetPath(path);
  const auto log = Drive(follower, Pose2(0.0, 0.0, 0.0), 60.0);
  ASSERT_TRUE(log.back().out.goal_reached);
  for (std::size_t i = 0; i + 1 < log.size(); ++i) {
    EXPECT_FALSE(log[i].out.goal_reached);
    EXPECT_GE(log[i].out.command.v, 0.0);
  }
  const Pose2 final_pose = log.back().pose;
  const double gap = 10.0 - final_pose.x;
  // At the end of the path, not goal_tolerance (let alone the original 2 m) before it.
  EXPECT_LE(std::abs(gap), 0.01);
  EXPECT_EQ(log.back().out.index, path.size() - 1);
  // The speed ramps down towards the end: below 0.5 m/s in the last 0.25 m.
  for (const Step& s : log) {
    if (10.0 - s.pose.x < 0.25) {
      EXPECT_LT(s.out.command.v, 0.5);
    }
  }
  // Once reached, the command stays zero.
  const FollowerOutput after = follower.Compute(final_pose, kPeriod);
  EXPECT_TRUE(after.goal_reached);
  EXPECT_EQ(after.command, core::Twist{});
  RecordProperty("final_gap_to_goal", std::to_string(gap));
}

TEST(PathFollower, NeverCommandsNegativeSpeedWhenFacingBackwards) {
  PathFollower follower({});
  follower.SetPath(Straight(10.0));
  const auto log = Drive(follower, Pose2(0.5, 0.2, core::kPi - 0.1), 60.0);
  ASSERT_TRUE(log.back().out.goal_reached);
  for (const Step& s : log) EXPECT_GE(s.out.command.v, 0.0);
  EXPECT_LT(std::abs(10.0 - log.back().pose.x), 0.1 + 1e-9);
}

// Overshoot (m) past the path when starting 0.5 m to its left, heading along it.
double Overshoot(const PathFollowerConfig& config) {
  PathFollower follower(config);
  follower.SetPath(Straight(20.0));
  const auto log = Drive(follower, Pose2(0.0, 0.5, 0.0), 60.0);
  double overshoot = 0.0;
  for (const Step& s : log) overshoot = std::max(overshoot, -s.pose.y);
  return overshoot;
}

TEST(PathFollower, DerivativeTermDampsOvershoot) {
  PathFollowerConfig without;
  without.kd_lateral = 0.0;
  without.kd_heading = 0.0;
  PathFollowerConfig with = without;
  with.kd_lateral = 0.8;
  const double o_without = Overshoot(without);
  const double o_with = Overshoot(with);
  EXPECT_GT(o_without, 0.02);
  EXPECT_LT(o_with, 0.5 * o_without);
  RecordProperty("overshoot_kd0", std::to_string(o_without));
  RecordProperty("overshoot_kd", std::to_string(o_with));
}

TEST(PathFollower, ProgressIsMonotonicOnAFigureEight) {
  // Two circles of radius 2 m tangent at the origin: the path passes the origin at its start,
  // in its middle and at its end.
  std::vector<Vec2> pts = ArcPoints(2.0, 2.0 * core::kPi, {0, 0}, 0, true, 0.25);
  const auto second = ArcPoints(2.0, 2.0 * core::kPi, {0, 0}, 0, false, 0.25);
  pts.insert(pts.end(), second.begin() + 1, second.end());
  const core::Path path = Polyline(pts, 0.25);
  const double length = path.Length();
  PathFollower follower({});
  follower.SetPath(path);
  const auto log = Drive(follower, Pose2(0.0, 0.0, 0.0), 120.0);
  ASSERT_TRUE(log.back().out.goal_reached);
  double max_error = 0.0;
  for (std::size_t i = 0; i < log.size(); ++i) {
    const FollowerOutput& out = log[i].out;
    max_error = std::max(max_error, DistanceToPath(path, log[i].pose.translation()));
    if (i > 0) {
      const FollowerOutput& prev = log[i - 1].out;
      EXPECT_GE(out.index, prev.index);
      EXPECT_LE(prev.remaining - out.remaining, 0.1) << "progress jumped at step " << i;
      EXPECT_GE(prev.remaining - out.remaining, 0.0);
    }
    if (i + 1 < log.size()) {
      EXPECT_FALSE(out.goal_reached) << "at step " << i;
    }
  }
  // The whole path was driven, not a shortcut through the crossing.
  double driven = 0.0;
  for (std::size_t i = 1; i < log.size(); ++i) {
    driven += (log[i].pose.translation() - log[i - 1].pose.translation()).norm();
  }
  EXPECT_GT(driven, 0.97 * length);
  EXPECT_LT(max_error, 0.05);
  // A global nearest-point search would have jumped: at the start the closest pose to the
  // robot is ambiguous between the start, the middle and the end of the path.
  EXPECT_LT((path[path.size() / 2].translation() - Vec2(0.0, 0.0)).norm(), 0.01);
  RecordProperty("max_error_on_figure_eight", std::to_string(max_error));
}

TEST(PathFollower, StartsFromTheFirstPathPoint) {
  // A path that starts with a 1 m leg to the left before heading off along +x.
  const core::Path path = Polyline({{0.0, 0.0}, {0.0, 1.0}, {5.0, 1.0}}, 0.25);
  PathFollower follower({});
  follower.SetPath(path);
  const auto log = Drive(follower, Pose2(0.0, 0.0, core::kPi / 2), 30.0);
  ASSERT_TRUE(log.back().out.goal_reached);
  EXPECT_EQ(log.front().out.index, 0u);
  EXPECT_NEAR(log.front().out.remaining, path.Length(), 1e-9);
  // The robot drove up the first leg instead of cutting towards the later points.
  double closest_to_leg = 1e9;
  for (const Step& s : log)
    closest_to_leg = std::min(closest_to_leg, (s.pose.translation() - Vec2(0.0, 0.5)).norm());
  EXPECT_LT(closest_to_leg, 0.05);
}

TEST(PathFollower, DoesNotReportGoalWhenNearTheEndPositionEarly) {
  // A loop whose end is 0.05 m from its start.
  std::vector<Vec2> pts = ArcPoints(2.0, 2.0 * core::kPi - 0.025, {0, 0}, 0, true, 0.25);
  PathFollower follower({});
  follower.SetPath(Polyline(pts, 0.25));
  const FollowerOutput first = follower.Compute(Pose2(0.0, 0.0, 0.0), kPeriod);
  EXPECT_FALSE(first.goal_reached);
  EXPECT_GT(first.command.v, 0.0);
}

TEST(PathFollower, ProgressWaitsOffThePathAndRejoinsAhead) {
  // A 30 m straight path; the robot is carried 5 m to the side and along it (a drive that left
  // the route): the progress does not creep after it, and the path's end stays far.
  PathFollower follower({});
  follower.SetPath(Straight(30.0));
  EXPECT_FALSE(follower.Compute(Pose2(1.0, 0.0, 0.0), kPeriod).off_path);
  FollowerOutput out;
  for (int i = 0; i < 200; ++i) out = follower.Compute(Pose2(1.0 + 0.1 * i, 5.0, 0.0), kPeriod);
  EXPECT_TRUE(out.off_path);
  EXPECT_NEAR(out.remaining, 29.0, 1e-9);
  // Back on the path 8 m further on (within rejoin_window): the progress moves there.
  out = follower.Compute(Pose2(9.0, 0.5, 0.0), kPeriod);
  EXPECT_FALSE(out.off_path);
  EXPECT_NEAR(out.remaining, 21.0, 1e-9);
  // Back on it 15 m further on, beyond rejoin_window: still waiting.
  out = follower.Compute(Pose2(24.0, 0.5, 0.0), kPeriod);
  EXPECT_TRUE(out.off_path);
  EXPECT_NEAR(out.remaining, 21.0, 1e-9);
}

TEST(PathFollower, SetPathAtStartsTheProgressThere) {
  PathFollower follower({});
  follower.SetPathAt(Straight(30.0), 26.0);
  EXPECT_NEAR(follower.Compute(Pose2(26.0, 0.3, 0.0), kPeriod).remaining, 4.0, 1e-9);
  // The progress only moves forward: a robot behind it is off the path ahead.
  EXPECT_TRUE(follower.Compute(Pose2(2.0, 0.0, 0.0), kPeriod).off_path);
  // Clamped to the path.
  follower.SetPathAt(Straight(30.0), 45.0);
  EXPECT_NEAR(follower.Compute(Pose2(30.0, 0.0, 0.0), kPeriod).remaining, 0.0, 1e-9);
}

TEST(PathFollower, EmptyPathIsReached) {
  PathFollower follower({});
  follower.SetPath(core::Path{});
  const FollowerOutput out = follower.Compute(Pose2(), kPeriod);
  EXPECT_TRUE(out.goal_reached);
  EXPECT_EQ(out.command, core::Twist{});
}

TEST(PathFollower, SinglePointPathIsApproached) {
  PathFollower follower({});
  follower.SetPath(core::Path({Pose2(1.0, 0.0, 0.0)}));
  const auto log = Drive(follower, Pose2(0.0, 0.0, 0.0), 20.0);
  ASSERT_TRUE(log.back().out.goal_reached);
  EXPECT_LT((log.back().pose.translation() - Vec2(1.0, 0.0)).norm(), 0.1 + 1e-9);
}

TEST(PathFollower, RejectsInvalidConfigNamingTheKey) {
  EXPECT_EQ(ValidationErrorKey<PathFollowerConfig>([](auto&) {}), kValid);
  EXPECT_EQ(ValidationErrorKey<PathFollowerConfig>([](auto& c) { c.look_ahead = 0.0; }),
            "look_ahead");
  EXPECT_EQ(ValidationErrorKey<PathFollowerConfig>([](auto& c) { c.kd_heading = 1.0; }),
            "kd_heading");
  EXPECT_EQ(ValidationErrorKey<PathFollowerConfig>([](auto& c) { c.min_speed = 2.0; }),
            "min_speed");
  EXPECT_EQ(
      ValidationErrorKey<PathFollowerConfig>([](auto& c) { c.goal_tolerance = std::nan(""); }),
      "goal_tolerance");
  EXPECT_EQ(ValidationErrorKey<PathFollowerConfig>([](auto& c) { c.kp_lateral = -1.0; }),
            "kp_lateral");
  EXPECT_EQ(ValidationErrorKey<PathFollowerConfig>([](auto& c) { c.rejoin_window = 1.0; }),
            "rejoin_window");
  EXPECT_EQ(
      ValidationErrorKey<PathFollowerConfig>([](auto& c) { c.progress_max_distance = 0.0; }),
      "progress_max_distance");
  PathFollowerConfig bad;
  bad.decel = 0.0;
  EXPECT_THROW(PathFollower{bad}, core::ConfigError);
}

}  // namespace
}  // namespace retrace::nav
