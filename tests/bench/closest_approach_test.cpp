// The closest approaches of passes (bench/crowd/closest_approach.hpp): pairs that come within the
// radius and change their order round the origin meanwhile, their smallest distance, ended when
// they part or when the measurement ends.

#include "bench/crowd/closest_approach.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace retrace::bench {
namespace {

using core::Vec2;

Vec2 OnRing(double radius, double angle) {
  return {radius * std::cos(angle), radius * std::sin(angle)};
}

TEST(ClosestApproach, TwoPeoplePassingEachOther) {
  // Round a ring of radius 5: one walks counter-clockwise on radius 5, the other clockwise on 5.6.
  ClosestApproachTracker tracker(2, 2.0);
  for (int step = 0; step <= 1000; ++step) {
    const double a = -0.5 + 0.001 * step;
    const std::vector<Vec2> p = {OnRing(5.0, a), OnRing(5.6, -a)};
    tracker.Update(p);
    if (step % 20 == 0) tracker.OpenEncounters(p);
  }
  const ClosestApproachStats s = tracker.Finish();
  EXPECT_EQ(s.encounters, 1);
  EXPECT_NEAR(s.mean, 0.6, 1e-9);  // abreast at angle 0
  EXPECT_NEAR(s.p05, 0.6, 1e-9);
}

TEST(ClosestApproach, NeighboursWhoDoNotPassAreNotCounted) {
  // Side by side, then one behind the other, all the way: no pass.
  ClosestApproachTracker tracker(3, 2.0);
  for (int step = 0; step <= 100; ++step) {
    const double a = 0.01 * step;
    const std::vector<Vec2> p = {OnRing(5.0, a), OnRing(5.5, a), OnRing(5.0, a - 0.1)};
    tracker.Update(p);
    tracker.OpenEncounters(p);
  }
  const ClosestApproachStats s = tracker.Finish();
  EXPECT_EQ(s.encounters, 0);
  EXPECT_TRUE(std::isnan(s.mean));
}

TEST(ClosestApproach, APassInProgressEndsWithTheMeasurement) {
  // One overtakes the other and is still beside it when the measurement ends.
  ClosestApproachTracker tracker(2, 1.0);
  for (int step = 0; step <= 30; ++step) {
    const std::vector<Vec2> p = {OnRing(5.0, 0.0), OnRing(5.4, -0.1 + 0.005 * step)};
    tracker.Update(p);
    tracker.OpenEncounters(p);
  }
  const ClosestApproachStats s = tracker.Finish();
  EXPECT_EQ(s.encounters, 1);
  EXPECT_NEAR(s.mean, 0.4, 1e-9);
}

TEST(ClosestApproach, APairPassingTwiceCountsTwice) {
  ClosestApproachTracker tracker(2, 1.0);
  // Passes at 0.5 m, parts, passes back at 0.7 m.
  const double b[] = {-0.05, 0.05, 0.5, 0.02, -0.02, -0.5};
  const double r[] = {5.5, 5.5, 5.5, 5.7, 5.7, 5.7};
  for (int i = 0; i < 6; ++i) {
    const std::vector<Vec2> p = {OnRing(5.0, 0.0), OnRing(r[i], b[i])};
    tracker.Update(p);
    tracker.OpenEncounters(p);
  }
  const ClosestApproachStats s = tracker.Finish();
  EXPECT_EQ(s.encounters, 2);
  EXPECT_GT(s.mean, 0.5);
  EXPECT_LT(s.mean, 0.72);
}

}  // namespace
}  // namespace retrace::bench
