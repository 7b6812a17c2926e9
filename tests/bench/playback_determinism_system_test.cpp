// Determinism of a playback with the whole navigation stack in the loop.
//
// PlaybackDeterminism.PinnedHashesOfTheSmallScenario pins hashes of the teaching drive of
// scenarios/small.yaml (partial maps: ground truth, odometry and each map's poses) and of the
// first 40 s of its playback run 0 (ground truth and estimate at every control tick): the
// simulator, the mapper, the localizer, the map server, the follower and the avoidance all
// feed into them. When a change is MEANT to alter trajectories, run this test, check that the
// change explains the difference, and paste the new hashes printed by the failure into the
// constants below, for GCC and for Clang. System tier: CI checks the GCC pin in the Release
// build; the Clang pin is checked by `ctest -L system` in a Clang build.
// (tests/sim/simulator_test.cpp pins the simulator alone.) Also: parallel runs write the same
// files as a serial run.

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "bench/engine/playback.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/teach_drive.hpp"
#include "core/rng.hpp"
#include "tests/support/small_run.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/trajectory_hash.hpp"

namespace retrace::bench {
namespace {

using retrace::testing::kSource;
using retrace::testing::SmallRunOptions;

std::uint64_t TeachHash(const TeachTrace& trace) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  auto mix = [&h](const core::Pose2& X) {
    const double values[] = {X.x, X.y, X.theta};
    h = core::HashBytes(values, sizeof values, h);
  };
  for (std::size_t i = 0; i < trace.X_WR.size(); ++i) {
    mix(trace.X_WR[i]);
    mix(trace.X_OR[i]);
  }
  for (const TeachMapTrace& map : trace.maps) {
    for (const core::Pose2& X : map.X_MR) mix(X);
  }
  return h;
}

TEST(PlaybackDeterminism, PinnedHashesOfTheSmallScenario) {
  // Bit-identical for the same binary; GCC and Clang generate different floating-point code, so
  // each has its own pin.
  constexpr std::uint64_t kPinnedTeachHash = 0x0b0c7becbcab9c14ULL;
#if defined(__clang__)
  constexpr std::uint64_t kPinnedPlaybackHash = 0x5d15224c97ca2b1bULL;
#else
  constexpr std::uint64_t kPinnedPlaybackHash = 0xc8cd20757608c514ULL;
#endif
  const Scenario scenario = LoadScenario(kSource / "scenarios/small.yaml");
  const TeachResult teach = RunTeachDrive(scenario, {MapMode::kPartial});
  const ModeTeach& partial = teach.modes.front();
  const RunTrace run = RunPlayback(scenario, partial.bundle, partial.trace, 0, 40.0);
  ASSERT_GT(run.samples.size(), 700u);  // 40 s at 20 Hz, unless the run ended early
  EXPECT_EQ(TeachHash(partial.trace), kPinnedTeachHash)
      << "new teach hash: 0x" << std::hex << TeachHash(partial.trace);
  EXPECT_EQ(testing::TrajectoryHash(run), kPinnedPlaybackHash)
      << "new playback hash: 0x" << std::hex << testing::TrajectoryHash(run);
}

std::string ReadWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(Episode, ParallelRunsGiveTheSameFilesAsASerialRun) {
  const retrace::testing::TempDir tmp;
  // Two modes of one teaching drive on three threads: runs of both modes interleave.
  ScenarioRunRequest serial_run = SmallRunOptions("partial", tmp.path() / "serial", 1);
  ScenarioRunRequest parallel_run = SmallRunOptions("partial", tmp.path() / "parallel", 3);
  serial_run.modes = parallel_run.modes = {"partial", "scan_matched"};
  // The figures are rendered after the runs and are not what is compared.
  serial_run.figures = parallel_run.figures = false;
  ASSERT_EQ(RunScenario(serial_run, "serial", nullptr).exit_code, 0);
  ASSERT_EQ(RunScenario(parallel_run, "parallel", nullptr).exit_code, 0);
  for (const char* mode : {"partial", "scan_matched"}) {
    for (const char* file :
         {"runs/0/gt.tum", "runs/0/est.tum", "runs/0/events.csv", "teach/gt.tum"}) {
      const std::filesystem::path rel = std::filesystem::path(mode) / file;
      SCOPED_TRACE(rel.string());
      const std::string serial = ReadWholeFile(tmp.path() / "serial" / rel);
      EXPECT_FALSE(serial.empty());
      EXPECT_EQ(serial, ReadWholeFile(tmp.path() / "parallel" / rel));
    }
  }
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "parallel/comparison.json"));
}

}  // namespace
}  // namespace retrace::bench
