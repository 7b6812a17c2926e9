// Scripted events in the simulator: pedestrian groups and static obstacles added during a run
// (Simulator::AddPedestrians, Simulator::AddObstacle), and what sees them: physics, LiDAR,
// StaticClearance and the crowd.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/rng.hpp"
#include "sim/lidar.hpp"
#include "sim/ray_caster.hpp"
#include "sim/simulator.hpp"
#include "sim/walk_planner.hpp"
#include "sim/world_file.hpp"
#include "tests/support/pedestrian_group.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/special_values.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::kSource;
using retrace::testing::kInf;

// A 20 m x 10 m room (inner faces at 0.1 and 19.9 / 9.9) and nothing else.
World EmptyRoom() {
  World world;
  WallConfig wall;
  wall.points = {{0.0, 0.0}, {20.0, 0.0}, {20.0, 10.0}, {0.0, 10.0}};
  wall.thickness = 0.2;
  wall.closed = true;
  world.config.walls.push_back(wall);
  world.geometry = BuildGeometry(world.config, ".");
  return world;
}

SimConfig NoiselessConfig() {
  SimConfig config;
  config.lidar.noise = LidarNoiseConfig{0.0, 0.0, 0.0, 0.0};
  return config;
}

BoxConfig Box(double x, double y, double sx, double sy, double yaw = 0.0) {
  BoxConfig b;
  b.center = {x, y};
  b.size = {sx, sy};
  b.yaw = yaw;
  return b;
}

CircleConfig Disc(double x, double y, double r) {
  CircleConfig c;
  c.center = {x, y};
  c.radius = r;
  return c;
}

using retrace::testing::Group;

// Steps with a zero command until the next LiDAR scan.
LidarReading NextScan(Simulator& sim) {
  for (;;) {
    SimStep step = sim.Step({});
    if (step.lidar) return std::move(*step.lidar);
  }
}

// Independent references: ray-box by slabs in the box frame, ray-circle by the quadratic.
double SlabHit(const Vec2& o_W, const Vec2& d_W, const BoxConfig& box) {
  const double c = std::cos(box.yaw), s = std::sin(box.yaw);
  const Vec2 r = o_W - box.center;
  const Vec2 o(c * r.x() + s * r.y(), -s * r.x() + c * r.y());
  const Vec2 d(c * d_W.x() + s * d_W.y(), -s * d_W.x() + c * d_W.y());
  double t_in = -kInf, t_out = kInf;
  for (int k = 0; k < 2; ++k) {
    const double h = 0.5 * box.size[k];
    if (d[k] == 0.0) {
      if (std::abs(o[k]) > h) return kInf;
      continue;
    }
    const double t1 = (-h - o[k]) / d[k], t2 = (h - o[k]) / d[k];
    t_in = std::max(t_in, std::min(t1, t2));
    t_out = std::min(t_out, std::max(t1, t2));
  }
  return (t_in >= 0.0 && t_in <= t_out) ? t_in : kInf;
}

double QuadraticHit(const Vec2& o, const Vec2& d, const CircleConfig& circle) {
  const Vec2 m = o - circle.center;
  const double b = m.dot(d), cc = m.squaredNorm() - circle.radius * circle.radius;
  const double disc = b * b - cc;
  if (disc < 0.0) return kInf;
  const double t = -b - std::sqrt(disc);
  return t >= 0.0 ? t : kInf;
}

// Checks every beam of `reading` (robot at X_WR, LiDAR mount identity): where the reference
// hit of the added obstacle is nearer than the walls, the truth is kStatic at that range and the
// noiseless reading equals it; elsewhere the walls. Returns the number of obstacle beams.
template <class Hit>
int CheckObstacleBeams(const LidarReading& reading, const core::Pose2& X_WR, const World& world,
                       const Hit& hit) {
  const RayCaster walls(world.geometry);
  int on_obstacle = 0;
  for (std::size_t i = 0; i < reading.scan.size(); ++i) {
    const double a = X_WR.theta + reading.scan.Angle(i);
    const Vec2 d(std::cos(a), std::sin(a));
    const double t_obstacle = hit(X_WR.translation(), d);
    const double t_wall = walls.Cast(X_WR.translation(), d, 30.0);
    const BeamTruth& truth = reading.truth[i];
    EXPECT_EQ(truth.source, BeamSource::kStatic) << "beam " << i;
    EXPECT_EQ(truth.pedestrian_id, -1);
    if (t_obstacle < t_wall) {
      ++on_obstacle;
      EXPECT_NEAR(truth.range, t_obstacle, 1e-9) << "beam " << i;
    } else {
      EXPECT_NEAR(truth.range, t_wall, 1e-9) << "beam " << i;
    }
    EXPECT_EQ(reading.scan.ranges[i], static_cast<float>(truth.range)) << "beam " << i;
  }
  return on_obstacle;
}

TEST(ScriptedObstacles, AddedBoxIsSeenByTheLidarAtTheExactRangeAsStatic) {
  const World world = EmptyRoom();
  const core::Pose2 X_WR(2.0, 5.0, 0.0);
  for (const double yaw : {0.0, 0.6}) {
    SCOPED_TRACE(yaw);
    Simulator sim(world, NoiselessConfig(), X_WR, core::Rng(3));
    const LidarReading before = NextScan(sim);
    const BoxConfig box = Box(6.0, 5.0, 1.0, 2.0, yaw);
    sim.AddObstacle(box);
    const LidarReading after = NextScan(sim);
    // The beam straight ahead: the wall at 17.9 m before, the box's near face after.
    const std::size_t ahead = after.scan.size() / 2;
    ASSERT_NEAR(after.scan.Angle(ahead), 0.0, 1e-12);
    EXPECT_NEAR(before.truth[ahead].range, 17.9, 1e-9);
    const double expected = yaw == 0.0 ? 3.5 : SlabHit(X_WR.translation(), {1.0, 0.0}, box);
    EXPECT_NEAR(after.truth[ahead].range, expected, 1e-9);
    EXPECT_EQ(after.truth[ahead].source, BeamSource::kStatic);
    const int n =
        CheckObstacleBeams(after, sim.RobotPose(), world,
                           [&](const Vec2& o, const Vec2& d) { return SlabHit(o, d, box); });
    EXPECT_GT(n, 60);  // ~2 m wide at 3.5-4.5 m: some 30 deg of 0.25 deg beams
  }
}

TEST(ScriptedObstacles, AddedCircleIsSeenByTheLidarAtTheExactRangeAsStatic) {
  const World world = EmptyRoom();
  const core::Pose2 X_WR(2.0, 5.0, 0.3);
  Simulator sim(world, NoiselessConfig(), X_WR, core::Rng(3));
  const CircleConfig circle = Disc(2.0 + 4.0 * std::cos(0.3), 5.0 + 4.0 * std::sin(0.3), 0.5);
  sim.AddObstacle(circle);
  const LidarReading reading = NextScan(sim);
  const std::size_t ahead = reading.scan.size() / 2;
  EXPECT_NEAR(reading.truth[ahead].range, 3.5, 1e-9);
  EXPECT_EQ(reading.truth[ahead].source, BeamSource::kStatic);
  const int n =
      CheckObstacleBeams(reading, sim.RobotPose(), world,
                         [&](const Vec2& o, const Vec2& d) { return QuadraticHit(o, d, circle); });
  EXPECT_GT(n, 50);  // 2 asin(0.5 / 4) = 14.4 deg of 0.25 deg beams
}

TEST(ScriptedObstacles, PedestrianInFrontOfAnAddedObstacleHidesItAndOneBehindIsHidden) {
  const World world = EmptyRoom();
  Lidar lidar(NoiselessConfig().lidar, world.geometry);
  StaticGeometry solid;
  solid.AddPolygon(BoxRing(Box(6.0, 5.0, 1.0, 2.0)));
  lidar.AddObstacles(solid);
  const core::Pose2 X_WR(2.0, 5.0, 0.0);
  const std::vector<DynamicCircle> people{{{4.0, 5.0}, 0.3, 7}, {{8.0, 5.5}, 0.3, 8}};
  core::Rng rng(1);
  const LidarReading r = lidar.Scan(X_WR, people, 0.0, rng);
  const std::size_t ahead = r.scan.size() / 2;
  EXPECT_EQ(r.truth[ahead].source, BeamSource::kPedestrian);
  EXPECT_EQ(r.truth[ahead].pedestrian_id, 7);
  EXPECT_NEAR(r.truth[ahead].range, 1.7, 1e-9);
  // Pedestrian 8 stands behind the box: no beam sees it.
  for (const BeamTruth& t : r.truth) EXPECT_NE(t.pedestrian_id, 8);
}

TEST(ScriptedObstacles, AnObstacleHiddenBehindAWallLeavesNoisyScansBitIdentical) {
  const World world = EmptyRoom();
  const core::Pose2 X_WR(2.0, 5.0, 0.0);
  Simulator plain(world, SimConfig{}, X_WR, core::Rng(5));
  Simulator hidden(world, SimConfig{}, X_WR, core::Rng(5));
  hidden.AddObstacle(Box(23.0, 5.0, 2.0, 2.0));  // outside the room
  hidden.AddObstacle(Disc(10.0, -3.0, 1.0));
  for (int k = 0; k < 3; ++k) {
    const LidarReading a = NextScan(plain);
    const LidarReading b = NextScan(hidden);
    ASSERT_EQ(a.scan.size(), b.scan.size());
    for (std::size_t i = 0; i < a.scan.size(); ++i) {
      ASSERT_EQ(std::bit_cast<std::uint32_t>(a.scan.ranges[i]),
                std::bit_cast<std::uint32_t>(b.scan.ranges[i]))
          << "beam " << i;
      ASSERT_EQ(a.truth[i].source, b.truth[i].source);
      ASSERT_EQ(a.truth[i].range, b.truth[i].range);
    }
  }
}

TEST(ScriptedObstacles, RobotDrivingIntoAnAddedObstacleCollidesAndStops) {
  const World world = EmptyRoom();
  struct Case {
    const char* name;
    bool box;
  };
  for (const Case c : {Case{"box", true}, Case{"circle", false}}) {
    SCOPED_TRACE(c.name);
    Simulator sim(world, NoiselessConfig(), core::Pose2(2.0, 5.0, 0.0), core::Rng(1));
    // Both present their surface at x = 4 on the robot's line.
    if (c.box) {
      sim.AddObstacle(Box(4.5, 5.0, 1.0, 2.0));
    } else {
      sim.AddObstacle(Disc(4.5, 5.0, 0.5));
    }
    std::vector<CollisionEvent> collisions;
    while (sim.time() < 6.0) {
      const SimStep step = sim.Step({0.5, 0.0});
      collisions.insert(collisions.end(), step.collisions.begin(), step.collisions.end());
    }
    ASSERT_FALSE(collisions.empty());
    const CollisionEvent& first = collisions.front();
    EXPECT_EQ(first.kind, CollisionKind::kStatic);
    EXPECT_EQ(first.pedestrian_id, -1);
    EXPECT_NEAR(first.point_W.x(), 4.0, 0.03);
    EXPECT_NEAR(first.point_W.y(), 5.0, 0.03);
    // 1.7 m to go: 0.25 s of acceleration, then 0.5 m/s.
    EXPECT_GT(first.time, 3.2);
    EXPECT_LT(first.time, 3.8);
    for (const CollisionEvent& e : collisions) EXPECT_EQ(e.kind, CollisionKind::kStatic);
    // Stopped against it (Box2D's 1 cm skin), not through it.
    const core::Pose2 X_WR = sim.RobotPose();
    EXPECT_LT(X_WR.x, 4.0 - 0.3 + 0.002);
    EXPECT_GT(X_WR.x, 4.0 - 0.3 - 0.03);
    EXPECT_NEAR(X_WR.y, 5.0, 0.01);
    EXPECT_LT(std::abs(sim.RobotTwist().v), 0.01);
  }
}

TEST(ScriptedObstacles, StaticClearanceCountsAddedObstacles) {
  const World world = EmptyRoom();
  Simulator sim(world, NoiselessConfig(), core::Pose2(2.0, 5.0, 0.0), core::Rng(1));
  EXPECT_NEAR(sim.StaticClearance({2.0, 5.0}), 1.9, 1e-12);
  EXPECT_NEAR(sim.StaticClearance({3.0, 5.0}), 2.9, 1e-12);
  EXPECT_NEAR(sim.StaticClearance({12.0, 5.0}), 4.9, 1e-12);
  EXPECT_EQ(sim.StaticClearance({20.0, 5.0}), 0.0);  // inside the wall
  EXPECT_TRUE(sim.added_obstacles().empty());

  sim.AddObstacle(Box(5.0, 5.0, 2.0, 2.0));
  sim.AddObstacle(Box(15.0, 5.0, 2.0, 2.0, 0.25 * core::kPi));
  sim.AddObstacle(Disc(10.0, 8.0, 0.5));
  EXPECT_NEAR(sim.StaticClearance({2.0, 5.0}), 1.9, 1e-12);  // the wall is still nearer
  EXPECT_NEAR(sim.StaticClearance({3.0, 5.0}), 1.0, 1e-12);
  EXPECT_EQ(sim.StaticClearance({5.0, 5.0}), 0.0);
  EXPECT_EQ(sim.StaticClearance({5.9, 4.1}), 0.0);
  EXPECT_NEAR(sim.StaticClearance({12.0, 5.0}), 3.0 - std::sqrt(2.0), 1e-12);  // the corner
  EXPECT_NEAR(sim.StaticClearance({10.0, 7.0}), 0.5, 1e-12);
  EXPECT_EQ(sim.StaticClearance({10.1, 8.1}), 0.0);
  EXPECT_EQ(sim.added_obstacles().polygons().size(), 2u);
  EXPECT_EQ(sim.added_obstacles().circles().size(), 1u);
}

TEST(ScriptedObstacles, ObstacleOverlappingTheRobotThrowsAndAddsNothing) {
  const World world = EmptyRoom();
  Simulator sim(world, NoiselessConfig(), core::Pose2(2.0, 5.0, 0.0), core::Rng(1));
  try {
    sim.AddObstacle(Box(2.5, 5.0, 0.6, 0.6));  // near face at 2.2: 0.2 m from the centre
    FAIL() << "expected a WorldError";
  } catch (const core::WorldError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("obstacle box at (2.500, 5.000)"), std::string::npos) << what;
    EXPECT_NE(what.find("robot at (2.000, 5.000)"), std::string::npos) << what;
    EXPECT_NE(what.find("clearance 0.200 m < robot radius 0.300 m"), std::string::npos) << what;
  }
  try {
    sim.AddObstacle(Disc(2.1, 5.0, 0.5));
    FAIL() << "expected a WorldError";
  } catch (const core::WorldError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("obstacle circle at (2.100, 5.000)"), std::string::npos) << what;
    EXPECT_NE(what.find("covers the robot's centre"), std::string::npos) << what;
  }
  EXPECT_TRUE(sim.added_obstacles().empty());
  EXPECT_NEAR(sim.StaticClearance({2.5, 5.0}), 2.4, 1e-12);
  // Bad shapes are configuration errors that name the key.
  try {
    sim.AddObstacle(Box(8.0, 5.0, 0.0, 1.0));
    FAIL() << "expected a ConfigError";
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "size");
  }
  try {
    sim.AddObstacle(Disc(8.0, std::nan(""), 1.0));
    FAIL() << "expected a ConfigError";
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "center");
  }
  // Nothing reached the physics or the LiDAR: the robot drives through where the box would be.
  while (sim.time() < 2.0) sim.Step({0.5, 0.0});
  EXPECT_TRUE(sim.collisions().empty());
  EXPECT_GT(sim.RobotPose().x, 2.8);
  // Close but clear is fine: a face 5 cm from the footprint.
  const double x = sim.RobotPose().x;
  EXPECT_NO_THROW(sim.AddObstacle(Box(x + 0.85, 5.0, 1.0, 1.0)));
}

TEST(ScriptedPedestrians, SpawnInsideTheRegionClearOfRobotWallsObstaclesAndEachOtherThenWalk) {
  const World world = EmptyRoom();
  for (const std::uint64_t seed : {8u, 9u, 10u, 11u, 12u}) {
    SCOPED_TRACE(seed);
    Simulator sim(world, NoiselessConfig(), core::Pose2(4.0, 5.0, 0.0), core::Rng(seed));
    EXPECT_EQ(sim.pedestrians().size(), 0);
    EXPECT_EQ(sim.pedestrians().planner(), nullptr);
    sim.AddObstacle(Box(10.0, 5.0, 3.0, 3.0));
    const PedestrianGroupConfig group = Group(10, {1.0, 1.0}, {19.0, 9.0});
    const std::vector<int> ids = sim.AddPedestrians(group);
    ASSERT_EQ(ids, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
    ASSERT_EQ(sim.pedestrians().size(), 10);
    ASSERT_NE(sim.pedestrians().planner(), nullptr);
    const CrowdConfig& crowd = sim.config().crowd;
    const std::vector<DynamicCircle> start = sim.PedestrianCircles();
    ASSERT_EQ(start.size(), 10u);
    for (std::size_t i = 0; i < start.size(); ++i) {
      const Vec2 p = start[i].center;
      EXPECT_EQ(start[i].id, ids[i]);
      EXPECT_EQ(sim.pedestrians().status()[i].group, 0);
      EXPECT_TRUE((Aabb{group.region_min, group.region_max}.Contains(p))) << p.transpose();
      // Free cells of the walk planner: radius + margin at the cell centre, minus half a diagonal.
      EXPECT_GE(sim.StaticClearance(p), 0.3 + crowd.planner.margin - 0.0708) << p.transpose();
      EXPECT_GE((p - Vec2(4.0, 5.0)).norm(), 0.3 + 0.3 + crowd.keep_clear_gap);
      for (std::size_t j = 0; j < i; ++j) {
        EXPECT_GE((p - start[j].center).norm(), 0.6 + crowd.spawn_gap);
      }
    }
    std::vector<DynamicCircle> last = start;
    std::vector<double> walked(start.size(), 0.0);
    while (sim.time() < 3.0) {
      sim.Step({});
      const std::vector<DynamicCircle> now = sim.PedestrianCircles();
      for (std::size_t i = 0; i < now.size(); ++i) {
        EXPECT_GE(sim.StaticClearance(now[i].center), 0.3 - 0.03) << "t = " << sim.time();
        walked[i] += (now[i].center - last[i].center).norm();
      }
      last = now;
    }
    // About 1.3 m/s after half a second of acceleration.
    // Up to speed (0.8 to 1.9 m/s) within a second, and nobody pauses right after appearing.
    for (std::size_t i = 0; i < walked.size(); ++i) {
      EXPECT_GT(walked[i], 1.5) << "pedestrian " << i;
      EXPECT_EQ(sim.pedestrians().status()[i].replans, 0) << "pedestrian " << i;
    }
  }
}

TEST(ScriptedPedestrians, AddedGroupsFollowTheWorldsGroupsAndLeaveTheirDrawsAlone) {
  const World world = LoadWorld(kSource / "worlds/test_room.yaml");
  const core::Pose2 start(2.0, 1.0, 0.0);
  Simulator plain(world, SimConfig{}, start, core::Rng(4));
  Simulator events(world, SimConfig{}, start, core::Rng(4));
  while (plain.time() < 1.0) {
    plain.Step({0.3, 0.0});
    events.Step({0.3, 0.0});
  }
  const std::vector<int> ids = events.AddPedestrians(Group(3, {5.0, 1.0}, {9.0, 5.0}));
  EXPECT_EQ(ids, (std::vector<int>{2, 3, 4}));
  ASSERT_EQ(events.pedestrians().size(), 5);
  for (int i = 0; i < 2; ++i) {
    const PedestrianStatus& a = plain.pedestrians().status()[static_cast<std::size_t>(i)];
    const PedestrianStatus& b = events.pedestrians().status()[static_cast<std::size_t>(i)];
    EXPECT_EQ(a.group, 0);
    EXPECT_EQ(a.desired_speed, b.desired_speed);
    EXPECT_EQ(a.goal, b.goal);
    EXPECT_EQ(a.path, b.path);
  }
  for (int i = 2; i < 5; ++i)
    EXPECT_EQ(events.pedestrians().status()[static_cast<std::size_t>(i)].group, 1);
}

TEST(ScriptedPedestrians, GroupsThatCannotBePlacedThrowAndAddNothing) {
  const World world = EmptyRoom();
  Simulator sim(world, NoiselessConfig(), core::Pose2(2.0, 5.0, 0.0), core::Rng(2));
  sim.AddObstacle(Box(10.0, 5.0, 4.0, 4.0));
  struct Case {
    const char* name;
    PedestrianGroupConfig group;
    const char* reason;
  };
  const Case cases[] = {
      {"inside an added obstacle", Group(1, {9.0, 4.0}, {11.0, 6.0}), "no free space"},
      {"inside a wall", Group(1, {19.95, 1.0}, {20.05, 9.0}), "no free space"},
      {"too full", Group(60, {15.0, 1.0}, {18.0, 4.0}), "too full"},
      {"on the robot", Group(2, {1.0, 4.0}, {3.0, 6.0}), "too full"},
      {"loop through the obstacle only",
       Group(1, {15.0, 4.0}, {16.0, 6.0}, PedestrianMode::kLoop, {{15.0, 5.0}, {10.0, 5.0}}),
       "loop waypoint 1"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    try {
      sim.AddPedestrians(c.group);
      FAIL() << "expected a WorldError";
    } catch (const core::WorldError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(c.reason), std::string::npos) << what;
      EXPECT_NE(what.find("added at t = 0.00 s"), std::string::npos) << what;
    }
    EXPECT_TRUE(sim.PedestrianCircles().empty());
    EXPECT_EQ(sim.pedestrians().size(), 0);
  }
  PedestrianGroupConfig bad = Group(1, {1.0, 1.0}, {5.0, 5.0});
  bad.count = -1;
  try {
    sim.AddPedestrians(bad);
    FAIL() << "expected a ConfigError";
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "count");
  }
  // The failures left the crowd usable.
  EXPECT_EQ(sim.AddPedestrians(Group(2, {14.0, 1.0}, {19.0, 9.0})).size(), 2u);
  EXPECT_TRUE(sim.AddPedestrians(Group(0, {14.0, 1.0}, {19.0, 9.0})).empty());
}

bool PathCrosses(const Vec2& from, const std::vector<Vec2>& path, const std::vector<Vec2>& ring) {
  Vec2 a = from;
  for (const Vec2& b : path) {
    for (std::size_t k = 0; k < ring.size(); ++k) {
      if (SegmentsIntersect(a, b, ring[k], ring[(k + 1) % ring.size()])) return true;
    }
    a = b;
  }
  return false;
}

TEST(ScriptedPedestrians, CrossingPedestriansRouteAroundAnObstacleAddedInTheirWay) {
  const World world = EmptyRoom();
  for (const std::uint64_t seed : {6u, 7u, 8u, 9u, 10u}) {
    SCOPED_TRACE(seed);
    Simulator sim(world, NoiselessConfig(), core::Pose2(2.0, 9.0, 0.0), core::Rng(seed));
    sim.AddPedestrians(
        Group(3, {2.0, 4.0}, {4.0, 6.0}, PedestrianMode::kLoop, {{17.0, 5.0}, {3.0, 5.0}}));
    while (sim.time() < 2.0) sim.Step({});
    const BoxConfig box = Box(10.0, 5.0, 1.0, 6.0);  // leaves 1.9 m above and below
    const std::vector<Vec2> ring = BoxRing(box);
    const Pedestrians& crowd = sim.pedestrians();
    bool some_path_crossed = false;
    for (const PedestrianStatus& s : crowd.status()) {
      some_path_crossed =
          some_path_crossed ||
          PathCrosses(sim.PedestrianCircles()[static_cast<std::size_t>(s.id)].center, s.path, ring);
    }
    EXPECT_TRUE(some_path_crossed);  // else the test shows nothing
    sim.AddObstacle(box);
    EXPECT_FALSE(crowd.planner()->IsFree({10.0, 5.0}));
    for (const PedestrianStatus& s : crowd.status()) {
      EXPECT_FALSE(
          PathCrosses(sim.PedestrianCircles()[static_cast<std::size_t>(s.id)].center, s.path, ring))
          << "pedestrian " << s.id;
    }
    std::vector<int> reached_before;
    for (const PedestrianStatus& s : crowd.status()) reached_before.push_back(s.goals_reached);
    double min_clearance = kInf;
    while (sim.time() < 62.0) {
      sim.Step({});
      for (const DynamicCircle& c : sim.PedestrianCircles()) {
        min_clearance = std::min(min_clearance, sim.StaticClearance(c.center) - c.radius);
      }
    }
    EXPECT_GT(min_clearance, -0.03);
    for (const PedestrianStatus& s : crowd.status()) {
      SCOPED_TRACE(s.id);
      // 14 m plus the detour at about 1.3 m/s: 4 or more legs in 60 s.
      EXPECT_GE(s.goals_reached - reached_before[static_cast<std::size_t>(s.id)], 3);
      EXPECT_EQ(s.goals_abandoned, 0);
    }
  }
}

TEST(ScriptedPedestrians, PedestriansUnderADroppedObstacleArePushedOutAndStayOut) {
  const World world = EmptyRoom();
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    Simulator sim(world, NoiselessConfig(), core::Pose2(2.0, 5.0, 0.0), core::Rng(seed));
    sim.AddPedestrians(Group(1, {9.9, 4.9}, {10.1, 5.1}));
    sim.AddPedestrians(Group(1, {11.1, 4.9}, {11.3, 5.1}));  // straddling the box's face
    sim.AddObstacle(Box(10.0, 5.0, 2.0, 2.0));
    while (sim.time() < 3.0) sim.Step({});
    while (sim.time() < 13.0) {
      sim.Step({});
      for (const DynamicCircle& c : sim.PedestrianCircles()) {
        ASSERT_GE(sim.StaticClearance(c.center), c.radius - 0.03)
            << "t = " << sim.time() << ", pedestrian " << c.id << " at " << c.center.transpose();
      }
    }
  }
}

// Hash of pedestrian positions and LiDAR ranges over a run with events at fixed steps.
std::uint64_t RunWithEvents(std::uint64_t seed) {
  const World world = LoadWorld(kSource / "worlds/test_room.yaml");
  Simulator sim(world, SimConfig{}, core::Pose2(2.0, 1.0, 0.0), core::Rng(seed));
  std::uint64_t h = core::HashBytes(nullptr, 0);
  for (int k = 0; sim.time() < 8.0 - 1e-9; ++k) {
    if (k == 100) sim.AddPedestrians(Group(3, {1.0, 3.0}, {9.0, 5.0}));
    if (k == 200) sim.AddObstacle(Disc(6.0, 1.0, 0.3));
    if (k == 250) {
      sim.AddPedestrians(
          Group(2, {8.0, 1.0}, {9.0, 2.0}, PedestrianMode::kLoop, {{8.5, 1.5}, {1.5, 4.5}}));
    }
    const SimStep step = sim.Step({k < 300 ? 0.3 : 0.0, 0.0});
    for (const DynamicCircle& c : sim.PedestrianCircles()) {
      const double xy[2] = {c.center.x(), c.center.y()};
      h = core::HashBytes(xy, sizeof(xy), h);
    }
    if (step.lidar) {
      const std::vector<float>& r = step.lidar->scan.ranges;
      h = core::HashBytes(r.data(), r.size() * sizeof(float), h);
    }
  }
  return h;
}

TEST(ScriptedEvents, SameSeedAndEventsGiveIdenticalRunsAndOtherSeedsDiffer) {
  const std::uint64_t a = RunWithEvents(21);
  EXPECT_EQ(a, RunWithEvents(21));
  EXPECT_NE(a, RunWithEvents(22));
}

TEST(WalkPlannerObstacles, BlockedCellsCutTheAreaAndPathsGoAround) {
  const World world = EmptyRoom();
  const GeometryIndex index(world.geometry);
  WalkPlanner planner(index, Aabb{{0.0, 0.0}, {20.0, 10.0}}, 0.3, WalkPlannerConfig{});
  const int free_before = planner.free_cell_count();
  EXPECT_EQ(planner.Component({2.0, 5.0}), planner.Component({18.0, 5.0}));
  StaticGeometry wall;
  wall.AddPolygon(BoxRing(Box(10.0, 4.0, 0.4, 8.0)));  // from y = 0 to 8: a gap at the top
  planner.AddObstacles(wall);
  EXPECT_LT(planner.free_cell_count(), free_before);
  EXPECT_FALSE(planner.IsFree({10.0, 5.0}));
  EXPECT_FALSE(planner.IsFree({10.52, 5.0}));  // cell centre 0.35 m from the face
  EXPECT_TRUE(planner.IsFree({10.68, 5.0}));   // 0.45 m: beyond radius + margin
  EXPECT_EQ(planner.Component({2.0, 5.0}), planner.Component({18.0, 5.0}));
  const auto path = planner.Plan({2.0, 5.0}, {18.0, 5.0});
  ASSERT_TRUE(path.has_value());
  EXPECT_FALSE(PathCrosses({2.0, 5.0}, *path, wall.polygons()[0]));
  // Closing the gap separates the two sides.
  StaticGeometry plug;
  plug.AddCircle({{10.0, 9.0}, 0.8});
  planner.AddObstacles(plug);
  EXPECT_NE(planner.Component({2.0, 5.0}), planner.Component({18.0, 5.0}));
  EXPECT_FALSE(planner.Plan({2.0, 5.0}, {18.0, 5.0}).has_value());
}

}  // namespace
}  // namespace retrace::sim
