// Determinism of the whole simulated world.
//
// SimulatorDeterminism.PinnedHashOfSixtySeconds pins a hash of 60 s of ground truth, pedestrians,
// LiDAR ranges and odometry. When a change is MEANT to alter simulation results (a new noise
// model, a different social force, a new default), run this test, check that the change
// explains the difference, and paste the new hash printed by the failure into kPinnedHash.

#include "sim/simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/errors.hpp"
#include "core/rng.hpp"
#include "io/route_file.hpp"
#include "sim/teacher.hpp"
#include "tests/support/source_dir.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::kSource;

struct RunSummary {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  int scans = 0;
  int odometry = 0;
  double distance = 0.0;
};

void Mix(RunSummary& s, double v) { s.hash = core::HashBytes(&v, sizeof v, s.hash); }

RunSummary Simulate(std::uint64_t seed, double seconds) {
  const World world = LoadWorld(kSource / "worlds/test_room.yaml");
  const auto route = io::ReadRouteFile(kSource / "worlds/routes/test_room_loop.txt");
  const core::Rng rng(seed);
  const core::Pose2 start(route[0].x(), route[0].y(), 0.0);
  Simulator sim(world, SimConfig{}, start, rng);
  Teacher teacher(route, TeacherConfig{}, rng.Split("teacher"));
  RunSummary s;
  core::Twist cmd;
  const int control_every = 5;  // 20 Hz control at 100 Hz physics
  core::Pose2 last = sim.RobotPose();
  for (int k = 0; sim.time() < seconds - 1e-9; ++k) {
    if (k % control_every == 0) cmd = teacher.Command(sim.RobotPose(), 0.05);
    const SimStep step = sim.Step(cmd);
    const core::Pose2 X_WR = sim.RobotPose();
    s.distance += core::Distance(last, X_WR);
    last = X_WR;
    Mix(s, X_WR.x);
    Mix(s, X_WR.y);
    Mix(s, X_WR.theta);
    for (const auto& c : sim.PedestrianCircles()) {
      Mix(s, c.center.x());
      Mix(s, c.center.y());
    }
    if (step.lidar) {
      ++s.scans;
      for (float r : step.lidar->scan.ranges) Mix(s, r);
    }
    if (step.odometry) {
      ++s.odometry;
      Mix(s, step.odometry->distance);
      Mix(s, step.odometry->dtheta);
    }
  }
  return s;
}

TEST(SimulatorDeterminism, SameSeedGivesIdenticalHashAndOtherSeedsDiffer) {
  const RunSummary a = Simulate(11, 60.0);
  const RunSummary b = Simulate(11, 60.0);
  const RunSummary c = Simulate(12, 60.0);
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_NE(a.hash, c.hash);
  EXPECT_EQ(a.scans, 60 * 20);
  EXPECT_EQ(a.odometry, 60 * 50);
  EXPECT_GT(a.distance, 15.0);  // the teacher actually drove
}

TEST(SimulatorDeterminism, PinnedHashOfSixtySeconds) {
  // Bit-identical for the same binary; GCC (the Release build) and Clang (the sanitizer build)
  // generate different floating-point code, so each has its own pin.
#if defined(__clang__)
  constexpr std::uint64_t kPinnedHash = 0xac4c2e4d2a5bc511ULL;
#else
  constexpr std::uint64_t kPinnedHash = 0xe33037b9c561a66aULL;
#endif
  const RunSummary a = Simulate(11, 60.0);
  EXPECT_EQ(a.hash, kPinnedHash) << "new hash: 0x" << std::hex << a.hash
                                 << " (see the header of this file before updating it)";
}

TEST(Simulator, RejectsARobotStartingInsideAnObstacle) {
  const World world = LoadWorld(kSource / "worlds/test_room.yaml");
  EXPECT_THROW(Simulator(world, SimConfig{}, core::Pose2(4.0, 2.0, 0.0), core::Rng(1)),
               core::WorldError);
  EXPECT_THROW(Simulator(world, SimConfig{}, core::Pose2(0.3, 3.0, 0.0), core::Rng(1)),
               core::WorldError);
}

TEST(Simulator, RejectsSensorRatesThatAreNotMultiplesOfTheStep) {
  const World world = LoadWorld(kSource / "worlds/test_room.yaml");
  SimConfig config;
  config.lidar.rate_hz = 30.0;  // 3.33 steps of 10 ms
  try {
    Simulator sim(world, config, core::Pose2(2.0, 1.0, 0.0), core::Rng(1));
    FAIL() << "expected a ConfigError";
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "lidar.rate_hz");
  }
}

}  // namespace
}  // namespace retrace::sim
