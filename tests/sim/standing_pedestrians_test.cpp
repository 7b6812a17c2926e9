// Pedestrian groups of mode `stand` (people standing still, e.g. the scenario's unmapped
// clutter): they stay where they spawned while others walk round them, and are pedestrians to
// the LiDAR.

#include <gtest/gtest.h>

#include <vector>

#include "sim/lidar.hpp"
#include "sim/pedestrians.hpp"
#include "sim/physics_world.hpp"
#include "tests/sim/add_box.hpp"
#include "tests/support/pedestrian_group.hpp"

namespace retrace::sim::standing_test {

using retrace::testing::Group;
using test_geometry::AddBox;

TEST(StandingPedestrians, StayPutWhileOthersWalkAndTheLidarSeesPeople) {
  StaticGeometry g;
  AddBox(g, -0.2, -0.2, 20.2, 0.0);
  AddBox(g, -0.2, 6.0, 20.2, 6.2);
  AddBox(g, -0.2, 0.0, 0.0, 6.0);
  AddBox(g, 20.0, 0.0, 20.2, 6.0);
  PhysicsWorld world(g);
  const std::vector<PedestrianGroupConfig> groups = {
      Group(1, {4.99, 2.99}, {5.01, 3.01}, PedestrianMode::kStand),
      Group(1, {11.99, 3.99}, {12.01, 4.01}, PedestrianMode::kStand),
      Group(6, {0.5, 0.5}, {19.5, 5.5})};
  Pedestrians crowd(groups, CrowdConfig{}, g, core::Rng(3), {}, world);
  ASSERT_EQ(crowd.size(), 8);
  for (int i = 0; i < 8; ++i) {  // what the social metrics tell them from walkers by
    EXPECT_EQ(crowd.status()[static_cast<std::size_t>(i)].standing, i < 2) << "person " << i;
  }
  const std::vector<DynamicCircle> start = world.PedestrianCircles();
  for (int step = 0; step < 3000; ++step) {  // 30 s
    crowd.Update(world);
    world.Step();
  }
  const std::vector<DynamicCircle> end = world.PedestrianCircles();
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(start[i].center.x(), i == 0 ? 5.0 : 12.0, 0.011);
    EXPECT_LT((end[i].center - start[i].center).norm(), 0.05) << "standing person " << i;
  }
  double walked = 0.0;
  for (int i = 2; i < 8; ++i) walked += (end[i].center - start[i].center).norm();
  EXPECT_GT(walked, 6.0);  // the walkers walk

  // Seen from 2 m away, a standing person is a pedestrian to the LiDAR.
  LidarConfig lidar_config;
  const Lidar lidar(lidar_config, g);
  core::Rng rng(1);
  const LidarReading reading = lidar.Scan(core::Pose2(3.0, 3.0, 0.0), end, 0.0, rng);
  int pedestrian_beams = 0;
  for (const BeamTruth& t : reading.truth) pedestrian_beams += t.source == BeamSource::kPedestrian;
  EXPECT_GT(pedestrian_beams, 0);
}

}  // namespace retrace::sim::standing_test
