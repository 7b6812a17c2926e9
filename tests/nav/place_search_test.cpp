#include "nav/place_search.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tests/nav/localizer_room.hpp"

namespace retrace::nav {
namespace {

// The room's map and a scan from a known pose; the prior is 0.9 m and 5° off.
TEST(PlaceSearch, FindsTheTruePoseWithinOneGridStepFromAPriorAMetreOff) {
  core::Rng rng(3);
  const std::vector<testing::Rect> rects = testing_room::RoomGeometry();
  const LikelihoodField field(testing_room::Rasterise(rects), LikelihoodFieldConfig{}, 30.0);
  const RobotGeometry robot = testing_room::TestRobot();
  const core::Pose2 truth(4.0, 3.0, 0.4);
  const core::LaserScan scan = testing_room::MakeScan(rects, {}, truth * robot.X_RL, rng);
  std::vector<double> xs, ys;
  ScanEndPoints(scan, robot, 10, &xs, &ys);
  ASSERT_GT(xs.size(), 50u);
  const std::vector<ScoredPlace> places = SearchPlaces(
      field, robot, xs, ys, core::Pose2(4.6, 2.3, 0.4 + core::DegToRad(5.0)), 1.5, 0.2);
  ASSERT_FALSE(places.empty());
  EXPECT_LT(core::Distance(places.front().X_MR, truth), 0.06);
  EXPECT_LT(std::abs(core::AngleDiff(places.front().X_MR.theta, truth.theta)), 0.02);
  for (std::size_t i = 1; i < places.size(); ++i) {
    EXPECT_LE(places[i].log_likelihood, places[i - 1].log_likelihood);
    EXPECT_GE(core::Distance(places[i].X_MR, places.front().X_MR), 0.5);
  }
}

TEST(PlaceSearch, ReturnsNothingForAScanWithoutEndPointsAndSharesParticlesEvenly) {
  const LikelihoodField field(testing_room::Rasterise(testing_room::RoomGeometry()),
                              LikelihoodFieldConfig{}, 30.0);
  EXPECT_TRUE(
      SearchPlaces(field, testing_room::TestRobot(), {}, {}, core::Pose2(), 1.0, 0.1).empty());
  core::Rng rng(1);
  const std::vector<ScoredPlace> two = {{core::Pose2(1, 1, 0), 0.0}, {core::Pose2(5, 5, 1), -1.0}};
  const std::vector<Particle> p = ParticlesAtPlaces(two, 100, 0.05, 0.01, rng);
  ASSERT_EQ(p.size(), 100u);
  int near_first = 0;
  for (const Particle& q : p) {
    EXPECT_DOUBLE_EQ(q.weight, 0.01);
    near_first += core::Distance(q.X_MR, two[0].X_MR) < 0.5 ? 1 : 0;
  }
  EXPECT_EQ(near_first, 50);
}

}  // namespace
}  // namespace retrace::nav
