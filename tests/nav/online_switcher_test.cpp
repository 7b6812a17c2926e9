// Online map switching: the recorder starts a new map by itself just before the robot comes back
// to where the current map has been, from its own poses and scans only.

#include "nav/online_switcher.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "nav/scan_constraint.hpp"
#include "nav/teach_recorder.hpp"
#include "tests/support/fake_scan.hpp"

namespace retrace::nav {
namespace {

using core::Pose2;
using core::Vec2;

// A circle of radius 10 m driven once round from (10, 0), 0.02 m per pose.
TEST(RevisitDetector, FiresJustBeforeACircleClosesAndNotBefore) {
  const OnlineSwitchingConfig config{3.0, 10.0, 0.03};
  RevisitDetector detector(config);
  const double circumference = 2.0 * core::kPi * 10.0;
  double fired = -1.0;
  for (double d = 0.0; d < circumference; d += 0.02) {
    const double a = d / 10.0;
    if (detector.OnPose(Pose2(10.0 * std::cos(a), 10.0 * std::sin(a), a + core::kPi / 2.0))) {
      fired = detector.travelled();
      break;
    }
  }
  ASSERT_GT(fired, 0.0) << "the circle closes but no revisit was seen";
  // Before it is within the radius of the start; the drift allowance (3 % of ~55 m) makes it
  // at most ~2 m earlier than that.
  const double chord_3m = circumference - 2.0 * 10.0 * std::asin(3.0 / 20.0);
  EXPECT_LT(fired, chord_3m);
  EXPECT_GT(fired, chord_3m - 2.5);
  EXPECT_NEAR(detector.travelled(), fired, 1e-12);
}

TEST(RevisitDetector, AStraightRoadAndATightTurnAreNoRevisit) {
  RevisitDetector detector(OnlineSwitchingConfig{});
  for (int i = 0; i < 5000; ++i) {
    EXPECT_FALSE(detector.OnPose(Pose2(0.02 * i, 0.0, 0.0)));
  }
  // A hairpin of radius 1 m comes back alongside 2 m away, right after: the road just driven.
  RevisitDetector hairpin(OnlineSwitchingConfig{});
  for (double d = 0.0; d < 3.14; d += 0.02) {
    EXPECT_FALSE(hairpin.OnPose(Pose2(std::sin(d), 1.0 - std::cos(d), d)));
  }
}

TEST(RevisitDetector, RefusesABadConfig) {
  EXPECT_THROW(RevisitDetector(OnlineSwitchingConfig{0.0, 10.0, 0.03}), core::ConfigError);
  EXPECT_THROW(RevisitDetector(OnlineSwitchingConfig{3.0, -1.0, 0.03}), core::ConfigError);
  EXPECT_THROW(RevisitDetector(OnlineSwitchingConfig{3.0, 10.0, 0.9}), core::ConfigError);
}

// A figure-eight (lemniscate of Gerono, 20 m half-width) in a walled hall with pillars, driven
// from its right end (20, 0) down through the crossing at the origin, round the left lobe, back
// through the crossing and round the right lobe towards the start again.
struct FigureEight {
  std::vector<testing::Segment> walls{{{-35.0, -20.0}, {35.0, -20.0}},
                                      {{35.0, -20.0}, {35.0, 20.0}},
                                      {{35.0, 20.0}, {-35.0, 20.0}},
                                      {{-35.0, 20.0}, {-35.0, -20.0}}};
  std::vector<testing::Circle> pillars;
  FigureEight() {
    for (double x = -30.0; x <= 30.0; x += 10.0) {
      pillars.push_back({{x, 14.0}, 0.4});
      pillars.push_back({{x + 5.0, -14.0}, 0.4});
    }
  }
  static Vec2 At(double t) { return {20.0 * std::sin(t), 20.0 * std::sin(t) * std::cos(t)}; }
  core::LaserScan Scan(const Pose2& X_WR) const {
    return testing::FakeScan(testing::ScanSpec{}, X_WR, [&](const Vec2& o, const Vec2& d) {
      double r = testing::NearestSegment(o, d, walls);
      for (const testing::Circle& c : pillars) r = std::min(r, testing::RayCircle(o, d, c));
      return r;
    });
  }
};

TEST(OnlineSwitching, AFigureEightSwitchesBeforeTheCrossing) {
  const FigureEight world;
  const OnlineSwitchingConfig online{3.0, 10.0, 0.03};
  TeachRecorder recorder(MapperConfig{}, RobotGeometry{}, std::nullopt, online);
  // Poses every ~2 cm of travel (t steps), a scan every 10th; the crossing passes at t = π
  // and t = 2π.
  std::vector<Pose2> poses;
  std::vector<double> travelled{0.0};
  const double t0 = core::kPi / 2.0, t1 = 2.0 * core::kPi + 0.4 * core::kPi;
  double second_crossing = 0.0;
  int n = 0;
  for (double t = t0; t < t1; t += 0.001, ++n) {
    const Vec2 p = FigureEight::At(t);
    const Vec2 ahead = FigureEight::At(t + 1e-4) - p;
    const Pose2 X_WR(p.x(), p.y(), std::atan2(ahead.y(), ahead.x()));
    if (!poses.empty())
      travelled.push_back(travelled.back() + (p - poses.back().translation()).norm());
    if (second_crossing == 0.0 && t >= 2.0 * core::kPi) second_crossing = travelled.back();
    poses.push_back(X_WR);
    recorder.OnPose(X_WR);  // exact odometry: O = W
    if (n % 10 == 0) recorder.OnScan(world.Scan(X_WR));
  }
  const TeachBundle bundle = recorder.Finish();

  // One switch is enough and it comes before the second pass through the crossing, far enough
  // ahead that map 0 never comes within the revisit radius of the crossing again.
  ASSERT_EQ(recorder.online_switches().size(), 1u);
  ASSERT_EQ(bundle.maps.size(), 2u);
  const OnlineSwitch& s = recorder.online_switches()[0];
  EXPECT_LT(s.travelled, second_crossing - online.revisit_radius);
  EXPECT_GT(s.travelled, second_crossing - online.revisit_radius - online.window - 3.0);
  const Pose2 X_OM1 = poses.front() * bundle.maps[0].X_MS;  // map 0's frame is the first pose
  EXPECT_GT(X_OM1.translation().norm(), online.revisit_radius);
  // The place chosen sees the hall's walls and pillars: well constrained.
  EXPECT_GT(s.constraint, 30.0);

  // Every pose went into a map, in order, and map 1 begins where map 0 ends (paper eq. 1).
  const std::vector<RecordedPose>& recorded = recorder.recorded_poses();
  ASSERT_EQ(recorded.size(), poses.size());
  std::size_t first_of_map1 = 0;
  while (recorded[first_of_map1].map == 0) ++first_of_map1;
  for (std::size_t i = first_of_map1; i < recorded.size(); ++i) EXPECT_EQ(recorded[i].map, 1u);
  EXPECT_LT(std::abs(travelled[first_of_map1] - s.travelled), 0.05);
  const Pose2 X_M1R = recorded.back().X_MR;
  const Pose2 expected = X_OM1.Inverse() * poses.back();
  EXPECT_NEAR(X_M1R.x, expected.x, 1e-6);
  EXPECT_NEAR(X_M1R.y, expected.y, 1e-6);
}

TEST(OnlineSwitching, ScansOfARobotStandingStillAreNotHeld) {
  TeachRecorder recorder(MapperConfig{}, RobotGeometry{}, std::nullopt, OnlineSwitchingConfig{});
  const FigureEight world;
  const Pose2 X_WR(20.0, 0.0, -core::kPi / 2.0);
  for (int i = 0; i < 100; ++i) {
    recorder.OnPose(X_WR);
    EXPECT_FALSE(recorder.OnScan(world.Scan(X_WR)));  // built later, behind the robot
  }
  const TeachBundle bundle = recorder.Finish();
  ASSERT_EQ(bundle.maps.size(), 1u);
  EXPECT_EQ(bundle.maps[0].path.size(), 1u);  // one keyframe: the start
  EXPECT_EQ(recorder.recorded_poses().size(), 100u);
}

}  // namespace
}  // namespace retrace::nav
