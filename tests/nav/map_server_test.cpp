#include "nav/map_server.hpp"
#include "tests/support/particle_covariance.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "core/rng.hpp"

namespace retrace::nav {
namespace {

void ExpectPoseNear(const core::Pose2& a, const core::Pose2& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(core::AngleDiff(a.theta, b.theta), 0.0, tol);
}

// A 20 m x 20 m map with a wall around it, origin at (-10, -10).
core::OccupancyGrid RoomMap() {
  core::OccupancyGrid grid(200, 200, 0.1, core::Vec2(-10.0, -10.0));
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 200; ++x) {
      const bool wall = x < 2 || y < 2 || x >= 198 || y >= 198;
      grid.SetProbability({x, y}, wall ? 0.95 : 0.05);
    }
  }
  return grid;
}

// The map server of a route with the given drift and revisit radius, the default options.
MapServer Server(TeachBundle bundle, double drift = 0.03, double radius = 3.0, bool loop = false,
                 const MapServerConfig& config = {}) {
  RouteLinkConfig link;
  link.drift = drift;
  link.revisit_radius = radius;
  return MapServer(std::move(bundle), config, link, loop);
}

// The robot's place on the current path for the estimate X_MR, travelling `travel`.
RoutePosition PlaceOn(const MapServer& server, const core::Pose2& X_MR, double max_distance,
                      Travel travel) {
  const core::PathProjection p = Project(server.current().path, X_MR.translation());
  RoutePosition pos;
  pos.map = server.index();
  pos.s = pos.s_extended = p.s;
  pos.distance = p.distance;
  pos.on_path = p.distance <= max_distance;
  pos.travel = travel;
  return pos;
}

// The map server's decision for a robot at X_MR travelling `travel`, without a scan.
MapDecision DecideAt(const MapServer& server, const FollowerOutput& f, const core::Pose2& X_MR,
                     double max_distance, Travel travel = Travel::kForward, bool lost = false) {
  return server.Decide(f, PlaceOn(server, X_MR, max_distance, travel), X_MR, max_distance, nullptr,
                       lost);
}

TeachBundle TwoMaps(const core::Pose2& X_M0S) {
  TeachBundle bundle;
  PartialMap m0;
  m0.grid = RoomMap();
  m0.path = core::Path({{0, 0, 0}, {2, 0, 0}, X_M0S});
  m0.X_MS = X_M0S;
  PartialMap m1;
  m1.grid = RoomMap();
  m1.path = core::Path({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}});
  m1.X_MS = core::Pose2(2, 0, 0);
  bundle.maps = {m0, m1};
  return bundle;
}

TEST(MapServer, EquationOneMapsTheSwitchPoseToIdentityAndKeepsRelativePoses) {
  const core::Pose2 X_MS(12.0, -3.0, 2.5);
  ExpectPoseNear(TransformToNextMap(X_MS, X_MS), core::Pose2::Identity(), 1e-12);
  // A pose 1 m ahead of the switch pose (along its heading) is (1, 0, 0) in the next map.
  ExpectPoseNear(TransformToNextMap(X_MS, X_MS * core::Pose2(1.0, 0.0, 0.0)),
                 core::Pose2(1.0, 0.0, 0.0), 1e-12);
  // Relative poses between two robots are preserved.
  const core::Pose2 a(11.0, -2.0, 2.0), b(13.0, -4.0, -1.0);
  ExpectPoseNear(core::Between(TransformToNextMap(X_MS, a), TransformToNextMap(X_MS, b)),
                 core::Between(a, b), 1e-12);
}

// The decision at the end of path k: map k+1, entered at its start, with eq. (1)'s transform.
RoutePlace NextAtEnd(const MapServer& server, const core::Pose2& X_MR) {
  FollowerOutput end;
  end.goal_reached = true;
  const MapDecision d = DecideAt(server, end, X_MR, 2.0);
  EXPECT_EQ(d.step, MapStep::kSwitch);
  return d.place;
}

TEST(MapServer, HandoverTransformsTheEstimateAndEveryParticleByEquationOne) {
  const core::Pose2 X_M0S(4.0, 1.0, 0.7);
  MapServer server = Server(TwoMaps(X_M0S));
  Localizer localizer(LocalizerConfig{}, RobotGeometry{}, core::Rng(3));
  PathFollower follower(PathFollowerConfig{});
  server.Start(localizer, follower);
  EXPECT_EQ(server.index(), 0u);
  EXPECT_FALSE(server.IsLast());

  // The robot stopped 0.2 m short of the switch pose, slightly off to the side.
  const core::Pose2 X_M0R = X_M0S * core::Pose2(-0.2, 0.05, 0.03);
  localizer.Initialize(X_M0R, 0.05, 0.02);
  const std::vector<Particle> before = localizer.particles();
  const core::Pose2 estimate_before = localizer.Estimate();

  const RoutePlace next = NextAtEnd(server, estimate_before);
  EXPECT_EQ(next.map, 1u);
  EXPECT_EQ(next.sigma, 0.0);
  const MapSwitch s = server.Switch(next, localizer, follower);
  EXPECT_EQ(s.from, 0u);
  EXPECT_EQ(s.to, 1u);
  EXPECT_TRUE(server.IsLast());
  ExpectPoseNear(s.X_MkR, estimate_before, 1e-12);
  ExpectPoseNear(s.X_MnR, TransformToNextMap(X_M0S, estimate_before), 1e-9);
  ExpectPoseNear(localizer.Estimate(), core::Pose2(-0.2, 0.05, 0.03), 0.05);
  const std::vector<Particle>& after = localizer.particles();
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < after.size(); ++i) {
    ExpectPoseNear(after[i].X_MR, TransformToNextMap(X_M0S, before[i].X_MR), 1e-9);
    EXPECT_DOUBLE_EQ(after[i].weight, before[i].weight);
  }
  // The follower now tracks path 1 from its first point.
  const FollowerOutput out = follower.Compute(localizer.Estimate(), 0.05);
  EXPECT_EQ(out.index, 0u);
  EXPECT_FALSE(out.goal_reached);
  EXPECT_NEAR(out.remaining, 2.0, 0.25);
}

TEST(MapServer, DecidesOnTheEndOfThePathByGoalOrRemainingArc) {
  MapServer server = Server(TwoMaps(core::Pose2(4.0, 0.0, 0.0)));
  const core::Pose2 X_MR(3.9, 0.0, 0.0);
  FollowerOutput out;
  out.goal_reached = false;
  out.remaining = 0.2;
  EXPECT_EQ(DecideAt(server, out, X_MR, 2.0).step, MapStep::kStay);
  out.remaining = kPathEndTolerance;  // a log's estimate that passed the end
  EXPECT_EQ(DecideAt(server, out, X_MR, 2.0).step, MapStep::kSwitch);
  out.off_path = true;  // the progress is at the end, but the robot is elsewhere: on path 0
  EXPECT_EQ(DecideAt(server, out, X_MR, 2.0).step, MapStep::kStay);
  out.off_path = false;
  out.remaining = 0.2;
  out.goal_reached = true;
  const MapDecision d = DecideAt(server, out, X_MR, 2.0);
  EXPECT_EQ(d.step, MapStep::kSwitch);
  EXPECT_EQ(d.place.map, 1u);
  EXPECT_THROW(Server(TeachBundle{}), core::ConfigError);
}

TEST(MapServer, WrapsOnlyALoopWhenLoopingIsOn) {
  // Paths of 4 m and 2 m along x: the route ends 6 m from where it began. Within a 1 m radius
  // it is no loop, within 100 m it is; looping off never wraps.
  const TeachBundle straight = TwoMaps(core::Pose2(4.0, 0.0, 0.0));
  MapServer line = Server(straight, 0.0, 1.0, true);
  EXPECT_FALSE(line.loops());
  Localizer localizer(LocalizerConfig{}, RobotGeometry{}, core::Rng(1));
  PathFollower follower{PathFollowerConfig{}};
  line.Start(localizer, follower);
  localizer.Initialize(core::Pose2::Identity(), 0.01, 0.01);
  line.Switch(NextAtEnd(line, core::Pose2(4.0, 0.0, 0.0)), localizer, follower);
  FollowerOutput end;
  end.goal_reached = true;
  EXPECT_EQ(DecideAt(line, end, core::Pose2::Identity(), 2.0).step, MapStep::kDone);
  MapServer ring = Server(straight, 0.0, 100.0, true);  // everything closes within 100 m
  EXPECT_TRUE(ring.loops());
  ring.Start(localizer, follower);
  ring.Switch(NextAtEnd(ring, core::Pose2(4.0, 0.0, 0.0)), localizer, follower);
  const MapDecision wrap = DecideAt(ring, end, core::Pose2::Identity(), 2.0);
  EXPECT_EQ(wrap.step, MapStep::kWrap);
  const MapSwitch s = ring.Switch(ring.WrapPlace(wrap), localizer, follower);
  EXPECT_EQ(s.to, 0u);
  EXPECT_EQ(ring.index(), 0u);
  EXPECT_FALSE(Server(straight, 0.0, 100.0, false).loops());
}

TEST(MapServer, SwitchesBackWhenTheRouteIsDrivenBackwards) {
  // Map 0's path ends at its switch pose (4, 0), turned by 90 degrees: map 1 starts there
  // heading +y in map 0. A robot in map 1 that drives back past map 1's start onto map 0's path
  // goes back to map 0, with its pose carried by X_{M_0 S}, and the follower's progress where
  // the robot is on path 0.
  const core::Pose2 X_M0S(4.0, 0.0, core::kPi / 2);
  TeachBundle bundle = TwoMaps(X_M0S);
  bundle.maps[0].path = core::Path({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, X_M0S});
  MapServer server = Server(bundle);
  Localizer localizer(LocalizerConfig{}, RobotGeometry{}, core::Rng(5));
  PathFollower follower(PathFollowerConfig{});
  server.Start(localizer, follower);
  localizer.Initialize(X_M0S, 0.01, 0.01);
  server.Switch(NextAtEnd(server, X_M0S), localizer, follower);

  // In map 1, on its path: stay. Map 0's (1.5, 0) facing back is (0, 2.5) in map 1, and 2.5 m
  // from map 1's path.
  FollowerOutput on = follower.Compute(core::Pose2(0.5, 0.0, 0.0), 0.05);
  EXPECT_EQ(DecideAt(server, on, core::Pose2(0.5, 0.0, 0.0), 2.0).step, MapStep::kStay);
  const core::Pose2 X_M1R = X_M0S.Inverse() * core::Pose2(1.5, 0.0, core::kPi);
  localizer.Initialize(X_M1R, 0.01, 0.01);
  FollowerOutput off = follower.Compute(X_M1R, 0.05);
  ASSERT_TRUE(off.off_path);
  const MapDecision back = DecideAt(server, off, X_M1R, 2.0, Travel::kBackward);
  ASSERT_EQ(back.step, MapStep::kSwitch);
  EXPECT_EQ(back.place.map, 0u);
  EXPECT_NEAR(back.place.s, 1.5, 1e-9);
  const core::Pose2 elsewhere(5.0, 5.0, 0.0);  // 5 m from both paths
  EXPECT_EQ(DecideAt(server, off, elsewhere, 2.0, Travel::kBackward).step, MapStep::kStay);

  const MapSwitch s = server.Switch(back.place, localizer, follower);
  EXPECT_EQ(s.from, 1u);
  EXPECT_EQ(s.to, 0u);
  EXPECT_EQ(server.index(), 0u);
  ExpectPoseNear(localizer.Estimate(), core::Pose2(1.5, 0.0, core::kPi), 0.05);
  EXPECT_NEAR(follower.Compute(localizer.Estimate(), 0.05).remaining, 2.5, 0.05);
  // Off map 0's path and near no other: it stays.
  FollowerOutput lost = follower.Compute(core::Pose2(1.5, 6.0, 0.0), 0.05);
  ASSERT_TRUE(lost.off_path);
  EXPECT_EQ(DecideAt(server, lost, core::Pose2(1.5, 6.0, 0.0), 2.0, Travel::kBackward).step,
            MapStep::kStay);
}

// Three maps of 10 m each: along +x in map 0, then up +y, then back along -x 10 m above map 0's
// path, so that path 2 passes 10 m beside path 0, 20 m further along the route.
TeachBundle ThreeMaps() {
  TeachBundle bundle;
  for (int k = 0; k < 3; ++k) {
    PartialMap m;
    m.grid = RoomMap();
    m.path = core::Path({{0, 0, 0}, {5, 0, 0}, {10, 0, 0}});
    m.X_MS = core::Pose2(10.0, 0.0, core::kPi / 2);
    bundle.maps.push_back(m);
  }
  bundle.linked = true;  // no revisit edges unless a test adds them
  return bundle;
}

TEST(MapServer, HandsOverTheMapWhosePathTheRobotIsOnByPlace) {
  // A robot in map 0 that leaves path 0 at (5, 0) and comes to (5, 9), 1 m from path 2, is on
  // map 2's path: the chain over map 1 holds 3 % of the 20 m of route between the two places.
  const core::Pose2 X_M0R(5.0, 9.0, core::kPi);
  FollowerOutput off;
  off.off_path = true;
  off.remaining = 5.0;
  MapServer server = Server(ThreeMaps());
  const MapDecision d = DecideAt(server, off, X_M0R, 2.0);
  ASSERT_EQ(d.step, MapStep::kSwitch);
  EXPECT_EQ(d.place.map, 2u);
  EXPECT_NEAR(d.place.s, 5.0, 1e-9);
  EXPECT_NEAR(d.place.distance, 1.0, 1e-9);
  EXPECT_NEAR(d.place.sigma, 0.03 * 20.0, 1e-9);
  EXPECT_FALSE(d.place.via_revisit);
  ExpectPoseNear(d.place.X_MR, core::Pose2(5.0, 1.0, 0.0), 1e-9);
  // The switch spreads the particles over that sigma.
  Localizer localizer(LocalizerConfig{}, RobotGeometry{}, core::Rng(2));
  PathFollower follower(PathFollowerConfig{});
  server.Start(localizer, follower);
  localizer.Initialize(X_M0R, 0.01, 0.01);
  server.Switch(d.place, localizer, follower);
  EXPECT_EQ(server.index(), 2u);
  EXPECT_NEAR(std::sqrt(testing::ParticleCovariance(localizer.particles(), localizer.Estimate())(0, 0)), 0.6, 0.1);

  // At 10 % drift that chain may be off by 2 m, more than max_sigma: no hand-over while the
  // localizer holds the robot in map 0. Lost, the place is searched. It stands for the robot on
  // path 2 (the settling belief searches around the path point), and is as far as 2 sigma may
  // take it from the path.
  const MapServer drifting = Server(ThreeMaps(), 0.1);
  EXPECT_EQ(DecideAt(drifting, off, X_M0R, 2.0).step, MapStep::kStay);
  const MapDecision searched = DecideAt(drifting, off, X_M0R, 2.0, Travel::kForward, true);
  ASSERT_EQ(searched.step, MapStep::kSwitch);
  EXPECT_EQ(searched.place.map, 2u);
  EXPECT_TRUE(drifting.Searched(searched.place));
  EXPECT_NEAR(searched.place.distance, 0.0, 1e-9);
  ExpectPoseNear(searched.place.X_MR, core::Pose2(5.0, 0.0, 0.0), 1e-9);
  ExpectPoseNear(searched.place.X_jk * X_M0R, searched.place.X_MR, 1e-9);
  EXPECT_EQ(DecideAt(drifting, off, core::Pose2(5.0, 17.0, core::kPi), 2.0, Travel::kForward, true)
                .step,
            MapStep::kStay);  // 7 m from path 2: more than 2 m + 2 sigma
  // Without the search, too long a chain: no hand-over.
  MapServerConfig no_search;
  no_search.search_sigma = 0.0;
  EXPECT_EQ(DecideAt(Server(ThreeMaps(), 0.1, 3.0, false, no_search), off, X_M0R, 2.0,
                     Travel::kForward, true)
                .step,
            MapStep::kStay);
  // A revisit edge registered between path 0 and path 2 at that place is exact there.
  TeachBundle linked = ThreeMaps();
  linked.revisits.push_back({0, 2, 5.0, 5.0, Server(ThreeMaps()).graph().Chain(0, 2)});
  const MapDecision via = DecideAt(Server(linked, 0.1), off, X_M0R, 2.0);
  ASSERT_EQ(via.step, MapStep::kSwitch);
  EXPECT_EQ(via.place.map, 2u);
  EXPECT_TRUE(via.place.via_revisit);
  EXPECT_NEAR(via.place.sigma, 0.1, 1e-9);
}

TEST(MapServer, StartsInTheMapNearestTheStart) {
  MapServer server = Server(ThreeMaps());
  const RoutePlace start = server.NearestMap(core::Pose2(3.0, 10.2, core::kPi));
  EXPECT_EQ(start.map, 2u);
  ExpectPoseNear(start.X_MR, core::Pose2(7.0, -0.2, 0.0), 1e-9);
  EXPECT_EQ(server.NearestMap(core::Pose2(3.0, 0.2, 0.0)).map, 0u);
  Localizer localizer(LocalizerConfig{}, RobotGeometry{}, core::Rng(2));
  PathFollower follower(PathFollowerConfig{});
  server.Start(localizer, follower, start.map, start.X_MR);
  EXPECT_EQ(server.index(), 2u);
  EXPECT_NEAR(follower.Compute(start.X_MR, 0.05).remaining, 3.0, 1e-9);
}

TEST(MapServer, EntersThePreviousMapAtItsEndWhenTheStartIsPassedBackwards) {
  // A robot in map 1 that drives back past map 1's start is at the end of map 0's path: eq. (1)
  // inverted carries its pose, X_{M_0 R} = X_{M_0 S} X_{M_1 R}, exactly as the switch forward did.
  const core::Pose2 X_M0S(4.0, 0.0, core::kPi / 2);
  MapServer server = Server(TwoMaps(X_M0S));
  Localizer localizer(LocalizerConfig{}, RobotGeometry{}, core::Rng(5));
  PathFollower follower(PathFollowerConfig{});
  server.Start(localizer, follower, 1);
  const core::Pose2 X_M1R(-0.1, 0.02, core::kPi);  // just behind map 1's start, facing back
  FollowerOutput f = follower.Compute(X_M1R, 0.05);
  RoutePosition pos = PlaceOn(server, X_M1R, 2.0, Travel::kBackward);
  pos.s_extended = -0.1;
  const MapDecision back = server.Decide(f, pos, X_M1R, 2.0);
  ASSERT_EQ(back.step, MapStep::kSwitch);
  EXPECT_EQ(back.place.map, 0u);
  EXPECT_EQ(back.travel, Travel::kBackward);
  EXPECT_EQ(back.place.sigma, 0.0);
  EXPECT_NEAR(back.place.s, server.bundle().maps[0].path.Length(), 1e-12);
  ExpectPoseNear(back.place.X_MR, X_M0S * X_M1R, 1e-12);
  // Driving forward at the same place, or backward mid-path, it stays.
  pos.travel = Travel::kForward;
  EXPECT_EQ(server.Decide(f, pos, X_M1R, 2.0).step, MapStep::kStay);
  pos = PlaceOn(server, core::Pose2(1.0, 0.0, core::kPi), 2.0, Travel::kBackward);
  EXPECT_EQ(server.Decide(f, pos, core::Pose2(1.0, 0.0, core::kPi), 2.0).step, MapStep::kStay);
  // Before map 0 there is nothing to go back to on a route driven once.
  server.Start(localizer, follower, 0);
  pos = PlaceOn(server, core::Pose2(-0.1, 0.0, core::kPi), 2.0, Travel::kBackward);
  EXPECT_EQ(server.Decide(f, pos, core::Pose2(-0.1, 0.0, core::kPi), 2.0).step, MapStep::kStay);
}

TEST(MapServer, AMapThatDoesNotCoverTheScanHandsOverOrSaysOffMap) {
  // Map 1's grid is the room; map 0's knows only a 2 m square round its origin. A scan of the
  // room's walls from (1, 0) ends in cells map 0 never observed.
  TeachBundle bundle = TwoMaps(core::Pose2(2.0, 0.0, 0.0));
  core::OccupancyGrid small(40, 40, 0.1, core::Vec2(-2.0, -2.0));
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 40; ++x) small.SetProbability({x, y}, 0.05);
  }
  bundle.maps[0].grid = small;
  std::vector<double> xs, ys;
  for (int i = 0; i < 36; ++i) {  // end points on the room's walls, 9 m away or so
    const double a = 2.0 * core::kPi * i / 36.0;
    const double r = 8.8 / std::max(std::abs(std::cos(a)), std::abs(std::sin(a)));
    xs.push_back(std::min(r, 12.0) * std::cos(a));
    ys.push_back(std::min(r, 12.0) * std::sin(a));
  }
  const ScanPoints scan{xs, ys, core::Pose2::Identity()};
  MapServer server = Server(bundle);
  Localizer localizer(LocalizerConfig{}, RobotGeometry{}, core::Rng(5));
  PathFollower follower(PathFollowerConfig{});
  server.Start(localizer, follower, 0);
  const core::Pose2 X_M0R(1.0, 0.0, 0.0);
  EXPECT_LT(server.Coverage(0, X_M0R, scan), 0.1);
  EXPECT_GT(server.Coverage(1, core::Pose2(-1.0, 0.0, 0.0), scan), 0.9);
  const FollowerOutput f = follower.Compute(X_M0R, 0.05);
  const RoutePosition pos = PlaceOn(server, X_M0R, 2.0, Travel::kForward);
  // Map 1's path (its start is map 0's (2, 0)) lies at the place and its grid covers the scan.
  const MapDecision d = server.Decide(f, pos, X_M0R, 2.0, &scan);
  EXPECT_LT(d.coverage, 0.1);
  ASSERT_EQ(d.step, MapStep::kSwitch);
  EXPECT_EQ(d.place.map, 1u);
  // With map 1's grid as small as map 0's, no map covers the place: off map.
  bundle.maps[1].grid = small;
  MapServer blind = Server(bundle);
  blind.Start(localizer, follower, 0);
  EXPECT_EQ(blind.Decide(f, pos, X_M0R, 2.0, &scan).step, MapStep::kOffMap);
  // Without a scan there is nothing to judge coverage by: the path holds the robot.
  EXPECT_EQ(blind.Decide(f, pos, X_M0R, 2.0).step, MapStep::kStay);
}

TEST(MapServer, OnAStreetDrivenOutAndBackTheLegDrivenTheRobotsWayIsChosen) {
  // Map 0 drives 10 m along +x, turns round, and map 1 drives the same street back: the two
  // paths lie on each other, one each way. A robot that comes onto the street facing -x takes
  // the leg whose direction matches its direction of travel.
  TeachBundle bundle = TwoMaps(core::Pose2(10.0, 0.0, core::kPi));
  bundle.maps[0].path = core::Path({{0, 0, 0}, {5, 0, 0}, {10, 0, 0}});
  bundle.maps[1].path = core::Path({{0, 0, 0}, {5, 0, 0}, {10, 0, 0}});
  bundle.linked = true;
  MapServer server = Server(bundle);
  const core::Pose2 X_M0R(5.0, 0.5, core::kPi);
  FollowerOutput f;
  f.remaining = 5.0;
  RoutePosition pos;  // off the stretch it was on (at s = 0), on no path there
  pos.on_path = false;
  pos.distance = 3.0;
  pos.travel = Travel::kForward;
  MapDecision d = server.Decide(f, pos, X_M0R, 2.0);
  ASSERT_EQ(d.step, MapStep::kSwitch);
  EXPECT_EQ(d.place.map, 1u);  // the way back, driven forward
  EXPECT_EQ(d.travel, Travel::kForward);
  ExpectPoseNear(d.place.X_MR, core::Pose2(5.0, -0.5, 0.0), 1e-9);
  pos.travel = Travel::kBackward;  // a drive that follows the route backwards: the way out
  d = server.Decide(f, pos, X_M0R, 2.0);
  ASSERT_EQ(d.step, MapStep::kSwitch);
  EXPECT_EQ(d.place.map, 0u);
  EXPECT_NEAR(d.place.s, 5.0, 1e-9);
}

}  // namespace
}  // namespace retrace::nav
