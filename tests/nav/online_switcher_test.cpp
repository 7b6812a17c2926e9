// Online map switching: the recorder starts a new map by itself just before the robot comes back
// to where the current map has been, from its own poses and scans only.

#include "nav/online_switcher.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
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
  EXPECT_THROW(RevisitDetector(OnlineSwitchingConfig{3.0, 10.0, 0.03, -1.0}), core::ConfigError);
  // 0.3 m of drift at 3 % is a 10 m map: no longer than the window it would choose its end in.
  try {
    RevisitDetector(OnlineSwitchingConfig{3.0, 10.0, 0.03, 0.3});
    ADD_FAILURE() << "a budget no longer than the window was accepted";
  } catch (const core::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("drift_budget"), std::string::npos) << e.what();
  }
  // No budget, or no drift to spend it on: maps end only before revisits.
  EXPECT_NO_THROW(RevisitDetector(OnlineSwitchingConfig{3.0, 10.0, 0.03, 0.0}));
  EXPECT_NO_THROW(RevisitDetector(OnlineSwitchingConfig{3.0, 10.0, 0.0, 9.0}));
  EXPECT_EQ(OnlineSwitchingConfig({3.0, 10.0, 0.0, 9.0}).MaxMapLength(),
            std::numeric_limits<double>::infinity());
}

// Out 10 m along a corridor and back 0.5 m beside the way out: a dead end.
double UTurnFires(const OnlineSwitchingConfig& config) {
  RevisitDetector detector(config);
  for (double d = 0.0; d < 20.0; d += 0.02) {
    const Pose2 X = d < 10.0 ? Pose2(d, 0.0, 0.0) : Pose2(20.0 - d, 0.5, core::kPi);
    if (detector.OnPose(X)) return detector.travelled();
  }
  return -1.0;
}

TEST(RevisitDetector, ARevisitIsAMapsEndOnlyOnceTheLoopIsInconsistent) {
  // Every revisit counts (tolerance 0): back within 3 m (plus the drift allowance) of the way
  // out where that lies more than 9 m of travel behind, 3.5 m into the way back.
  EXPECT_NEAR(UTurnFires({3.0, 10.0, 0.03, 12.0, 0.0}), 13.5, 0.2);
  // 0.5 m at 3 %: only a part of the way out 16.7 m of travel behind counts, so the detector
  // fires 7 m into the way back, 3 m from the dead end's start.
  const OnlineSwitchingConfig drift_aware{3.0, 10.0, 0.03, 12.0, 0.5};
  EXPECT_NEAR(drift_aware.MinMapLength(), 16.667, 1e-3);
  const double fired = UTurnFires(drift_aware);
  EXPECT_GT(fired, drift_aware.MinMapLength());
  EXPECT_LT(fired, 18.0);
  // 1 m: the whole 20 m there and back is consistent.
  EXPECT_LT(UTurnFires({3.0, 10.0, 0.03, 12.0, 1.0}), 0.0);
  // A tolerance the drift budget cannot hold is refused, naming it.
  try {
    RevisitDetector(OnlineSwitchingConfig{3.0, 10.0, 0.03, 12.0, 13.0});
    ADD_FAILURE() << "a tolerance beyond the budget was accepted";
  } catch (const core::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("tolerance"), std::string::npos) << e.what();
  }
}

TEST(RevisitDetector, TheDriftBudgetIsReachedAfterBudgetOverDriftMetresOfTheMap) {
  // 6 m at 3 %: 200 m of travel per map.
  RevisitDetector detector(OnlineSwitchingConfig{3.0, 10.0, 0.03, 6.0});
  EXPECT_DOUBLE_EQ(detector.config().MaxMapLength(), 200.0);
  int i = 0;
  for (; !detector.DriftBudgetReached(); ++i) detector.OnPose(Pose2(0.1 * i, 0.0, 0.0));
  EXPECT_NEAR(detector.travelled(), 200.0, 0.1 + 1e-9);
  // A map begun 5 m back has 195 m to go.
  detector.StartMap(detector.travelled() - 5.0);
  EXPECT_FALSE(detector.DriftBudgetReached());
  const double start = detector.travelled() - 5.0;
  for (; !detector.DriftBudgetReached(); ++i) detector.OnPose(Pose2(0.1 * i, 0.0, 0.0));
  EXPECT_NEAR(detector.travelled() - start, 200.0, 0.1 + 1e-9);
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
  EXPECT_EQ(s.reason, SwitchReason::kRevisit);
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

// A straight road 1 km long between two walls 10 m apart, with a post every 7 m on the left
// and every 11 m on the right (so that how well a place is constrained along the road varies):
// no place is ever driven twice.
struct StraightRoad {
  static constexpr double kLength = 1000.0;
  std::vector<testing::Segment> walls{{{-50.0, -5.0}, {kLength + 50.0, -5.0}},
                                      {{-50.0, 5.0}, {kLength + 50.0, 5.0}}};
  std::vector<testing::Circle> posts;
  StraightRoad() {
    for (double x = 0.0; x <= kLength + 40.0; x += 7.0) posts.push_back({{x, 4.0}, 0.3});
    for (double x = 3.0; x <= kLength + 40.0; x += 11.0) posts.push_back({{x, -4.0}, 0.3});
  }
  core::LaserScan Scan(const Pose2& X_WR) const {
    std::vector<testing::Circle> near;  // only the posts in range: keeps the test fast
    for (const testing::Circle& c : posts)
      if (std::abs(c.c.x() - X_WR.x) < 31.0) near.push_back(c);
    testing::ScanSpec spec;
    spec.beams = 541;
    return testing::FakeScan(spec, X_WR, [&](const Vec2& o, const Vec2& d) {
      double r = testing::NearestSegment(o, d, walls);
      for (const testing::Circle& c : near) r = std::min(r, testing::RayCircle(o, d, c));
      return r;
    });
  }
};

// Drives the road with exact odometry (O = W), a pose every 0.125 m and a scan every 0.5 m
// (binary fractions: the distances driven add up exactly).
std::vector<OnlineSwitch> DriveStraightRoad(const OnlineSwitchingConfig& online,
                                            std::size_t* maps) {
  const StraightRoad road;
  TeachRecorder recorder(MapperConfig{}, RobotGeometry{}, std::nullopt, online);
  for (int i = 0; 0.125 * i <= StraightRoad::kLength; ++i) {
    const Pose2 X_WR(0.125 * i, 0.0, 0.0);
    recorder.OnPose(X_WR);
    if (i % 4 == 0) recorder.OnScan(road.Scan(X_WR));
  }
  *maps = recorder.Finish().maps.size();
  return recorder.online_switches();
}

TEST(OnlineSwitching, AStraightKilometreWithoutRevisitIsCutAtEveryDriftBudget) {
  // 3 m of drift at 3 %: a map every 100 m at most.
  const OnlineSwitchingConfig online{3.0, 10.0, 0.03, 3.0};
  std::size_t maps = 0;
  const std::vector<OnlineSwitch> switches = DriveStraightRoad(online, &maps);
  ASSERT_EQ(maps, switches.size() + 1);
  // Each map ends inside the window behind the place its budget ran out: between 100 m less
  // the window (and a step of the detector's trail, and a pose) and 100 m after it began.
  EXPECT_GE(switches.size(), 10u);
  EXPECT_LE(switches.size(), 12u);
  double start = 0.0;
  for (const OnlineSwitch& s : switches) {
    EXPECT_EQ(s.reason, SwitchReason::kDriftBudget);
    EXPECT_LE(s.travelled - start, online.MaxMapLength()) << "at " << s.travelled;
    EXPECT_GE(s.travelled - start, online.MaxMapLength() - online.window - 0.5 - 0.125)
        << "at " << s.travelled;
    // ... at a place whose scan sees the posts, not at the window's edge by default.
    EXPECT_GT(s.constraint, 0.0);
    start = s.travelled;
  }
  EXPECT_GT(StraightRoad::kLength - start, 0.0);
  EXPECT_LE(StraightRoad::kLength - start, online.MaxMapLength());
}

TEST(OnlineSwitching, TheChosenPlaceIsTheBestConstrainedOfTheWindow) {
  const StraightRoad road;
  const OnlineSwitchingConfig online{3.0, 10.0, 0.03, 3.0};
  std::size_t maps = 0;
  const std::vector<OnlineSwitch> switches = DriveStraightRoad(online, &maps);
  ASSERT_FALSE(switches.empty());
  // The first switch: its budget ran out at 100 m; no scan of the window before that (every
  // 0.5 m, as the recorder compares them) is better constrained than the one chosen.
  const OnlineSwitch& s = switches.front();
  const double end = online.MaxMapLength();
  for (double d = end - online.window + 0.5; d < end - 0.5; d += 0.5) {
    const double c = ScanConstraint(road.Scan(Pose2(d, 0.0, 0.0)), RobotGeometry{});
    EXPECT_LE(c, s.constraint + 1e-9) << "a better place at " << d << " m than " << s.travelled;
  }
}

TEST(OnlineSwitching, WithoutABudgetAStraightKilometreIsOneMap) {
  std::size_t maps = 0;
  EXPECT_TRUE(DriveStraightRoad(OnlineSwitchingConfig{3.0, 10.0, 0.03, 0.0}, &maps).empty());
  EXPECT_EQ(maps, 1u);
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
