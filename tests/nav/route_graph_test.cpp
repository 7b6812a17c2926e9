// The route graph: revisit edges found and registered between partial maps of the same place,
// and the registration that refuses an ambiguous place.
#include "nav/route_graph.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/angle.hpp"
#include "nav/map_registration.hpp"

namespace retrace::nav {
namespace {

using core::Pose2;
using core::Vec2;

struct WallSegment {
  Vec2 a, b;
};

double DistanceToWall(const Vec2& p, const WallSegment& s) {
  const Vec2 d = s.b - s.a;
  const double t = std::clamp((p - s.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (s.a + t * d)).norm();
}

// A grid of its own frame B, of the walls given in frame A, X_AB being B's frame in A: what a
// partial map of the same place holds when its frame has drifted.
core::OccupancyGrid DrawnGrid(const std::vector<WallSegment>& walls_A, const Pose2& X_AB) {
  core::OccupancyGrid grid(800, 800, 0.05, Vec2(-20.0, -20.0));
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const Vec2 c_B = grid.CellToWorld({x, y});
      const Vec2 c_A = (X_AB * Pose2(c_B.x(), c_B.y(), 0.0)).translation();
      double d = 1e9;
      for (const WallSegment& s : walls_A) d = std::min(d, DistanceToWall(c_A, s));
      grid.SetProbability({x, y}, d < 0.05 ? 0.95 : 0.1);
    }
  }
  return grid;
}

// A room with a doorway, a pillar-like box and an alcove: no two nearby poses see the same.
std::vector<WallSegment> RoomWalls() {
  return {{{-8, -6}, {8, -6}},  {{8, -6}, {8, 6}},    {{8, 6}, {-2, 6}},   {{-4, 6}, {-8, 6}},
          {{-8, 6}, {-8, -6}},  {{1, -1}, {2.5, -1}}, {{2.5, -1}, {2.5, 1}}, {{-8, 0}, {-6, 0}},
          {{-6, 0}, {-6, -2}}};
}

// Two long parallel walls: a corridor, the same at every point along its axis.
std::vector<WallSegment> CorridorWalls() { return {{{-10, -1.5}, {10, -1.5}}, {{-10, 1.5}, {10, 1.5}}}; }

TEST(MapRegistration, FindsTheTransformBetweenTwoMapsOfTheSamePlace) {
  const Pose2 X_AB(1.2, -0.7, 0.08);
  const core::OccupancyGrid A = DrawnGrid(RoomWalls(), Pose2::Identity());
  const core::OccupancyGrid B = DrawnGrid(RoomWalls(), X_AB);
  const LikelihoodField field(A, LikelihoodFieldConfig{}, 30.0);
  // The chain's prior is off by 0.6 m and 3 degrees: the drift between the two visits.
  const Pose2 prior = Pose2(0.5, -0.3, core::DegToRad(3.0)) * X_AB;
  MapRegistrationConfig config;
  const std::optional<MapRegistration> r = RegisterMaps(field, B, Vec2(0.0, 0.0), prior, config);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(r->X_AB.x, X_AB.x, 0.03);
  EXPECT_NEAR(r->X_AB.y, X_AB.y, 0.03);
  EXPECT_NEAR(core::AngleDiff(r->X_AB.theta, X_AB.theta), 0.0, 0.005);
  EXPECT_GT(r->inliers, 0.8);
  EXPECT_LT(r->runner_up, r->inliers - config.ambiguity_margin);
}

TEST(MapRegistration, RefusesACorridorSeenAlongItsAxis) {
  const Pose2 X_AB(0.4, 0.1, 0.02);
  const core::OccupancyGrid A = DrawnGrid(CorridorWalls(), Pose2::Identity());
  const core::OccupancyGrid B = DrawnGrid(CorridorWalls(), X_AB);
  const LikelihoodField field(A, LikelihoodFieldConfig{}, 30.0);
  EXPECT_FALSE(RegisterMaps(field, B, Vec2(0.0, 0.0), X_AB, MapRegistrationConfig{}).has_value());
  // And a place without walls near it.
  const core::OccupancyGrid empty(400, 400, 0.05, Vec2(-10.0, -10.0));
  EXPECT_FALSE(
      RegisterMaps(field, empty, Vec2(0.0, 0.0), X_AB, MapRegistrationConfig{}).has_value());
}

TEST(LinkRoute, RegistersTheRevisitOfALoopAndNothingAlongTheWay) {
  // Map 0 drives 30 m round the room's south and east; map 1 comes back to map 0's start from
  // the north after 40 m more. The chain of switch poses carries 0.5 m and 2 degrees of drift:
  // the maps are drawn in frames that disagree by that much.
  const Pose2 drift(0.5, 0.3, core::DegToRad(2.0));
  TeachBundle bundle;
  PartialMap m0;
  m0.grid = DrawnGrid(RoomWalls(), Pose2::Identity());
  m0.path = core::Path({{-4, -3, 0}, {4, -3, 0}, {5, -3, core::kPi / 2}, {5, 3, core::kPi / 2}});
  m0.X_MS = m0.path.back();
  bundle.maps.push_back(m0);
  // Map 1's frame is its start X_M0S as the chain says; the world sees it where drift puts it.
  const Pose2 X_M0M1_true = drift * m0.X_MS;
  PartialMap m1;
  m1.grid = DrawnGrid(RoomWalls(), X_M0M1_true);
  const std::vector<Pose2> back_W = {m0.X_MS, {5, 4, core::kPi}, {-4, 4, core::kPi},
                                     {-4, -2.5, -core::kPi / 2}};
  std::vector<Pose2> back_M1;
  for (const Pose2& X : back_W) back_M1.push_back(X_M0M1_true.Inverse() * X);
  m1.path = core::Path(back_M1);
  m1.X_MS = back_M1.back();
  bundle.maps.push_back(m1);

  RouteLinkConfig config;
  config.drift = 0.03;
  LinkRoute(bundle, config);
  EXPECT_TRUE(bundle.linked);
  // One edge (edges of a pair lie `spacing` apart along path 1), near the end of path 1 and the
  // start of path 0: along the way the two paths never come back to each other.
  ASSERT_GE(bundle.revisits.size(), 1u);
  for (const RevisitEdge& e : bundle.revisits) {
    EXPECT_EQ(e.a, 0u);
    EXPECT_EQ(e.b, 1u);
    // The registered transform is the true one, not the chain's.
    EXPECT_NEAR(e.X_ab.x, X_M0M1_true.x, 0.05);
    EXPECT_NEAR(e.X_ab.y, X_M0M1_true.y, 0.05);
    EXPECT_NEAR(core::AngleDiff(e.X_ab.theta, X_M0M1_true.theta), 0.0, 0.01);
  }
}

}  // namespace
}  // namespace retrace::nav
