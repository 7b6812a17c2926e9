#include "sim/walk_planner.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "sim/geometry_index.hpp"
#include "tests/sim/add_box.hpp"

namespace retrace::sim {
namespace {

using test_geometry::AddBox;

// A 10 m x 6 m room split at x = 5 by a wall with a door of `door` m at y in [1, 1 + door].
StaticGeometry RoomWithDoor(double door) {
  StaticGeometry g;
  AddBox(g, -0.2, -0.2, 10.2, 0.0);
  AddBox(g, -0.2, 6.0, 10.2, 6.2);
  AddBox(g, -0.2, 0.0, 0.0, 6.0);
  AddBox(g, 10.0, 0.0, 10.2, 6.0);
  AddBox(g, 4.9, 0.0, 5.1, 1.0);
  AddBox(g, 4.9, 1.0 + door, 5.1, 6.0);
  return g;
}

const Aabb kArea{{-0.5, -0.5}, {10.5, 6.5}};
constexpr double kRadius = 0.3;

// Minimum clearance (brute force) along a polyline, sampled every 1 cm.
double MinClearanceAlong(const StaticGeometry& g, const Vec2& from, const std::vector<Vec2>& path) {
  double best = 1e9;
  Vec2 a = from;
  for (const Vec2& b : path) {
    const int n = std::max(1, static_cast<int>((b - a).norm() / 0.01));
    for (int i = 0; i <= n; ++i) best = std::min(best, g.Clearance(a + (b - a) * (double(i) / n)));
    a = b;
  }
  return best;
}

TEST(WalkPlanner, PlansThroughTheDoorWithFewWaypointsAndSafeClearance) {
  const StaticGeometry g = RoomWithDoor(1.2);
  const GeometryIndex index(g);
  const WalkPlannerConfig config;
  const WalkPlanner planner(index, kArea, kRadius, config);
  const Vec2 from(1.0, 5.0), to(9.0, 5.0);
  const auto path = planner.Plan(from, to);
  ASSERT_TRUE(path.has_value());
  EXPECT_LE(path->size(), 4u);
  EXPECT_EQ(path->back(), to);
  // It goes through the door.
  bool through_door = false;
  for (const Vec2& p : *path)
    through_door |= p.y() > 1.0 && p.y() < 2.2 && std::abs(p.x() - 5.0) < 1.0;
  EXPECT_TRUE(through_door);
  const double clearance = MinClearanceAlong(g, from, *path);
  RecordProperty("min_clearance", std::to_string(clearance));
  EXPECT_GE(clearance, kRadius + config.margin - config.cell_size / std::sqrt(2.0) - 1e-9);
  // Every leg is a line of sight.
  Vec2 a = from;
  for (const Vec2& b : *path) {
    EXPECT_TRUE(planner.LineOfSight(a, b));
    a = b;
  }
}

TEST(WalkPlanner, GoesStraightWhenNothingIsInTheWay) {
  const StaticGeometry g = RoomWithDoor(1.2);
  const WalkPlanner planner(GeometryIndex(g), kArea, kRadius, {});
  const auto path = planner.Plan({1.0, 1.0}, {4.0, 5.0});
  ASSERT_TRUE(path.has_value());
  ASSERT_EQ(path->size(), 1u);
  EXPECT_EQ(path->front(), Vec2(4.0, 5.0));
}

TEST(WalkPlanner, ClosedWallSeparatesComponentsAndHasNoPath) {
  const StaticGeometry g = RoomWithDoor(0.0);
  const WalkPlanner planner(GeometryIndex(g), kArea, kRadius, {});
  EXPECT_GE(planner.Component({1.0, 1.0}), 0);
  EXPECT_NE(planner.Component({1.0, 1.0}), planner.Component({9.0, 1.0}));
  EXPECT_EQ(planner.Component({1.0, 1.0}), planner.Component({4.0, 5.5}));
  EXPECT_FALSE(planner.Plan({1.0, 1.0}, {9.0, 1.0}).has_value());
}

TEST(WalkPlanner, DoorNarrowerThanThePedestrianIsImpassable) {
  const StaticGeometry g = RoomWithDoor(0.55);
  const WalkPlanner planner(GeometryIndex(g), kArea, kRadius, {});
  EXPECT_FALSE(planner.Plan({1.0, 1.0}, {9.0, 1.0}).has_value());
}

TEST(WalkPlanner, CellsInsideAndNearSolidsAreNotFree) {
  StaticGeometry g = RoomWithDoor(1.2);
  AddBox(g, 1.0, 2.0, 3.0, 4.0);  // a big table
  g.AddCircle({{7.5, 3.0}, 0.5});
  const WalkPlanner planner(GeometryIndex(g), kArea, kRadius, {});
  EXPECT_FALSE(planner.IsFree({2.0, 3.0}));   // deep inside the table
  EXPECT_FALSE(planner.IsFree({3.2, 3.0}));   // 0.2 m from it
  EXPECT_TRUE(planner.IsFree({3.5, 3.0}));    // 0.5 m from it
  EXPECT_FALSE(planner.IsFree({7.5, 3.0}));   // inside the pillar
  EXPECT_FALSE(planner.IsFree({-1.0, 3.0}));  // outside the area
  EXPECT_FALSE(planner.IsFree({5.0, 4.0}));   // inside the partition
  EXPECT_EQ(planner.Component({2.0, 3.0}), -1);
}

TEST(WalkPlanner, SnapsAGoalInsideAWallToTheNearestFreeCell) {
  const StaticGeometry g = RoomWithDoor(1.2);
  const WalkPlanner planner(GeometryIndex(g), kArea, kRadius, {});
  const auto path = planner.Plan({1.0, 5.0}, {4.95, 4.0});  // goal inside the partition
  ASSERT_TRUE(path.has_value());
  EXPECT_TRUE(planner.IsFree(path->back()));
  EXPECT_LT((path->back() - Vec2(4.95, 4.0)).norm(), 0.6);
  EXPECT_LT(path->back().x(), 5.0);  // on the near side
}

TEST(WalkPlanner, SamplesFreeReachablePointsUniformly) {
  const StaticGeometry g = RoomWithDoor(0.0);
  const WalkPlanner planner(GeometryIndex(g), kArea, kRadius, {});
  core::Rng rng(7);
  const int left = planner.Component({1.0, 1.0});
  const Aabb region{{0.0, 0.0}, {10.0, 6.0}};
  int count = 0;
  double mean_y = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const auto p = planner.SampleFreePoint(region, rng, 1000, left);
    ASSERT_TRUE(p.has_value());
    EXPECT_TRUE(planner.IsFree(*p));
    EXPECT_EQ(planner.Component(*p), left);
    EXPECT_LT(p->x(), 5.0);
    EXPECT_GE(g.Clearance(*p), kRadius);
    mean_y += p->y();
    ++count;
  }
  EXPECT_NEAR(mean_y / count, 3.0, 0.1);
  // A region entirely inside a wall has no free point.
  EXPECT_FALSE(planner.SampleFreePoint({{4.95, 2.0}, {5.05, 3.0}}, rng, 100).has_value());
}

TEST(WalkPlanner, IsDeterministic) {
  const StaticGeometry g = RoomWithDoor(1.0);
  const WalkPlanner a(GeometryIndex(g), kArea, kRadius, {});
  const WalkPlanner b(GeometryIndex(g), kArea, kRadius, {});
  EXPECT_EQ(a.free_cell_count(), b.free_cell_count());
  const auto pa = a.Plan({1.0, 5.5}, {9.0, 0.5});
  const auto pb = b.Plan({1.0, 5.5}, {9.0, 0.5});
  ASSERT_TRUE(pa && pb);
  ASSERT_EQ(pa->size(), pb->size());
  for (std::size_t i = 0; i < pa->size(); ++i) EXPECT_EQ((*pa)[i], (*pb)[i]);
}

// A generated campus of 500 m x 270 m (a real 1.9 km route) needs 13.5 million cells of 0.1 m:
// its pedestrians are planned on 0.13 m cells instead, within the 8 million cell limit.
TEST(WalkPlanner, LargeAreasArePlannedOnCoarserCells) {
  const WalkPlannerConfig config;
  EXPECT_EQ(PlanningCellSize({{0.0, 0.0}, {50.0, 50.0}}, config), config.cell_size);
  const double cell = PlanningCellSize({{0.0, 0.0}, {500.0, 270.0}}, config);
  EXPECT_DOUBLE_EQ(cell, 0.13);
  EXPECT_LE(std::ceil(500.0 / cell) * std::ceil(270.0 / cell), 8e6);
  EXPECT_GT(std::ceil(500.0 / 0.12) * std::ceil(270.0 / 0.12), 8e6);  // the finest that fits
}

TEST(WalkPlanner, RejectsHugeAreasAndBadConfig) {
  const StaticGeometry g = RoomWithDoor(1.0);
  const GeometryIndex index(g);
  // 5 km x 5 km would need cells of 1.8 m, which close doors: refused before anything is built.
  EXPECT_THROW(WalkPlanner(index, {{0.0, 0.0}, {5000.0, 5000.0}}, kRadius, {}), core::WorldError);
  EXPECT_THROW(WalkPlanner(index, {{0.0, 0.0}, {0.0, 1.0}}, kRadius, {}), core::WorldError);
  WalkPlannerConfig bad;
  bad.cell_size = 0.0;
  EXPECT_THROW(WalkPlanner(index, kArea, kRadius, bad), core::ConfigError);
}

TEST(WalkPlanner, PlanningAreaCoversRegionsAndPoints) {
  const Aabb a = PlanningArea({{{0.0, 0.0}, {2.0, 3.0}}}, {{5.0, -1.0}}, 1.0);
  EXPECT_EQ(a.min, Vec2(-1.0, -2.0));
  EXPECT_EQ(a.max, Vec2(6.0, 4.0));
}

}  // namespace
}  // namespace retrace::sim
