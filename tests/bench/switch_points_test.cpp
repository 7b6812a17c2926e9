#include "bench/engine/switch_points.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include "core/errors.hpp"
#include "io/route_file.hpp"
#include "tests/support/source_dir.hpp"

namespace retrace::bench {
namespace {

using core::Vec2;
using ::testing::HasSubstr;

using retrace::testing::kSource;

// A 40 m square driven twice from (0, 0), counter-clockwise, stopping at (0, 20) on the way
// down its west side: 300 m. The second lap revisits the first.
std::vector<Vec2> DoubleSquare() {
  const std::vector<Vec2> lap{{0, 0}, {40, 0}, {40, 40}, {0, 40}};
  std::vector<Vec2> route;
  for (int k = 0; k < 2; ++k) route.insert(route.end(), lap.begin(), lap.end());
  route.push_back({0, 20});
  return route;
}

// A figure-eight of two circles of radius 20 m touching at the origin, driven `laps` times:
// counter-clockwise round the north circle, then clockwise round the south one, heading east
// through the origin each time. Every circle is 125.7 m.
std::vector<Vec2> FigureEight(int laps) {
  std::vector<Vec2> route{{0, 0}};
  constexpr int kSteps = 72;  // 5 degrees
  constexpr double kRadius = 20.0;
  for (int lap = 0; lap < laps; ++lap) {
    for (double side : {1.0, -1.0}) {
      for (int i = 1; i <= kSteps; ++i) {
        // Angle travelled from the origin; the centre is at (0, side * R).
        const double a = 2.0 * std::numbers::pi * i / kSteps;
        route.push_back({kRadius * std::sin(a), side * kRadius * (1.0 - std::cos(a))});
      }
    }
  }
  return route;
}

TEST(RouteLength, SumsTheSegments) {
  EXPECT_DOUBLE_EQ(RouteLength(DoubleSquare()), 300.0);
  EXPECT_DOUBLE_EQ(RouteLength({{1, 1}}), 0.0);
}

TEST(CheckSwitchPoints, WarnsWhenAMapRevisitsItsOwnPath) {
  const auto warnings = CheckSwitchPoints(DoubleSquare(), {}, 3.0);
  ASSERT_EQ(warnings.size(), 1u);
  // The first lap comes back within 3 m of its start 3 m before closing the square (157 m).
  EXPECT_THAT(warnings[0], HasSubstr("partial map 0"));
  EXPECT_THAT(warnings[0], HasSubstr("from 157.1 m on"));
  EXPECT_THAT(warnings[0], HasSubstr("too late"));

  // Switching after the revisit started only moves the problem into map 0's tail.
  const auto late = CheckSwitchPoints(DoubleSquare(), {200.0}, 3.0);
  ASSERT_EQ(late.size(), 1u);
  EXPECT_THAT(late[0], HasSubstr("partial map 0 (route 0 m to 200 m)"));
}

TEST(CheckSwitchPoints, AcceptsASwitchBeforeTheRevisit) {
  EXPECT_THAT(CheckSwitchPoints(DoubleSquare(), {150.0}, 3.0), ::testing::IsEmpty());
  EXPECT_THAT(CheckSwitchPoints(DoubleSquare(), {80.0, 150.0, 250.0}, 3.0), ::testing::IsEmpty());
  // A route that never comes back needs no switch at all.
  EXPECT_THAT(CheckSwitchPoints({{0, 0}, {100, 0}, {100, 50}}, {}, 5.0), ::testing::IsEmpty());
}

TEST(CheckSwitchPoints, AUTurnIsNotARevisitButDrivingBackIs) {
  // Out 30 m, a tight U-turn 4 m wide, and back: the two sides of the U are within the radius
  // but only a few metres apart along the route; driving back along the way out is a revisit.
  const std::vector<Vec2> out_and_back{{0, 0}, {30, 0}, {30, 4}, {0, 4}};
  const std::vector<Vec2> u_turn_only{{0, 0}, {30, 0}, {30, 4}, {28, 4}};
  EXPECT_THAT(CheckSwitchPoints(u_turn_only, {}, 5.0), ::testing::IsEmpty());
  EXPECT_THAT(CheckSwitchPoints(out_and_back, {}, 5.0), ::testing::SizeIs(1));
}

TEST(CheckSwitchPoints, RejectsSwitchPointsOutsideTheRouteOrOutOfOrder) {
  const auto route = DoubleSquare();
  for (const std::vector<double>& bad : {std::vector<double>{0.0},
                                         {-5.0},
                                         {300.0},
                                         {450.0},
                                         {100.0, 100.0},
                                         {150.0, 100.0},
                                         {std::nan("")}}) {
    try {
      CheckSwitchPoints(route, bad, 3.0);
      ADD_FAILURE() << "expected a ConfigError for " << ::testing::PrintToString(bad);
    } catch (const core::ConfigError& e) {
      EXPECT_EQ(e.key_path(), "route.switch_points");
      if (bad.size() == 1) {
        EXPECT_THAT(e.what(), HasSubstr("length 300 m"));
      }
    }
  }
  EXPECT_THROW(CheckSwitchPoints(route, {}, 0.0), core::ConfigError);
  EXPECT_THROW(CheckSwitchPoints({{0, 0}}, {}, 3.0), core::ConfigError);
}

TEST(SuggestSwitchPoints, SwitchesJustBeforeTheSecondLapOfADoubleLoop) {
  const auto points = SuggestSwitchPoints(DoubleSquare(), 3.0);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_GT(points[0], 156.0);
  EXPECT_LT(points[0], 157.1);
  EXPECT_THAT(CheckSwitchPoints(DoubleSquare(), points, 3.0), ::testing::IsEmpty());
}

TEST(SuggestSwitchPoints, StartsANewMapBeforeEachPassThroughTheCrossingOfAFigureEight) {
  const double circle = 2.0 * std::numbers::pi * 20.0;
  const auto once = FigureEight(1);
  // One figure-eight ends where it started: a map per circle, the second ending with a short
  // revisit of the crossing.
  const auto points = SuggestSwitchPoints(FigureEight(2), 3.0);
  ASSERT_EQ(points.size(), 4u);
  for (std::size_t k = 0; k < points.size(); ++k) {
    // Shortly before each pass through the origin: each map starts a little before the
    // crossing, so it comes back near its own start a little earlier each time.
    EXPECT_LT(points[k], (k + 1) * circle) << k;
    EXPECT_GT(points[k], (k + 1) * circle - 15.0) << k;
  }
  EXPECT_THAT(CheckSwitchPoints(FigureEight(2), points, 3.0), ::testing::IsEmpty());
  EXPECT_THAT(CheckSwitchPoints(FigureEight(2), {}, 3.0), ::testing::SizeIs(1));
  EXPECT_THAT(SuggestSwitchPoints(once, 3.0), ::testing::SizeIs(2));
}

TEST(SuggestSwitchPoints, GivesNothingForARouteThatNeverComesBack) {
  EXPECT_THAT(SuggestSwitchPoints({{0, 0}, {50, 0}, {50, 50}, {0, 50}, {0, 10}}, 5.0),
              ::testing::IsEmpty());
}

TEST(SuggestSwitchPoints, ShippedCampusRouteNeedsFourPartialMaps) {
  const auto route = io::ReadRouteFile(kSource / "worlds/routes/campus.txt");
  for (double radius : {3.0, 5.0, 10.0}) {
    const auto points = SuggestSwitchPoints(route, radius);
    EXPECT_EQ(points.size(), 3u) << "revisit radius " << radius;
    EXPECT_THAT(CheckSwitchPoints(route, points, radius), ::testing::IsEmpty());
  }
}

}  // namespace
}  // namespace retrace::bench
