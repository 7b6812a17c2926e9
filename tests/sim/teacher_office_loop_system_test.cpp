// The simulated teacher drives the whole office loop (system tier: a 150 m drive per seed, 18 s
// under the sanitizers).

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/errors.hpp"
#include "core/rng.hpp"
#include "io/route_file.hpp"
#include "sim/simulator.hpp"
#include "sim/teacher.hpp"
#include "tests/support/source_dir.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::kSource;

TEST(Simulator, TeacherDrivesTheOfficeLoopToTheEndWithoutTouchingAWall) {
  const World world = LoadWorld(kSource / "worlds/office.yaml");
  const auto route = io::ReadRouteFile(kSource / "worlds/routes/office_loop.txt");
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    const core::Rng rng(seed);
    const core::Vec2 d = route[1] - route[0];
    const core::Pose2 start(route[0].x(), route[0].y(), std::atan2(d.y(), d.x()));
    Simulator sim(world, SimConfig{}, start, rng);
    Teacher teacher(route, TeacherConfig{}, rng.Split("teacher"));
    core::Twist cmd;
    for (int k = 0; !teacher.Done() && sim.time() < 400.0; ++k) {
      if (k % 5 == 0) cmd = teacher.Command(sim.RobotPose(), 0.05);
      sim.Step(cmd);
    }
    EXPECT_TRUE(teacher.Done());
    EXPECT_NEAR(teacher.RouteLength(), 152.5, 0.5);
    for (const auto& c : sim.collisions())
      EXPECT_NE(c.kind, CollisionKind::kStatic) << "t = " << c.time;
    // Odometry drifts, but like a real robot: centimetres to a few metres after 150 m.
    const core::Pose2 X_WR_odometry = start * sim.OdometryPose();
    const double drift = core::Distance(X_WR_odometry, sim.RobotPose());
    EXPECT_GT(drift, 0.02);
    EXPECT_LT(drift, 6.0);
  }
}

}  // namespace
}  // namespace retrace::sim
