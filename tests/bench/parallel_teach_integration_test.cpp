// A teaching drive whose recorders are shared out over several threads
// (RunTeachDrive(..., threads)) builds the same teach bundles, traces and switch decisions, bit
// for bit, as the drive on one thread; an error of the drive still comes out with helpers.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "bench/engine/scenario.hpp"
#include "bench/engine/teach_drive.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "tests/support/source_dir.hpp"

namespace retrace::bench {
namespace parallel_teach_test {  // not anonymous: unity builds batch test files together

using retrace::testing::kSource;

Scenario ParallelTeachScenario(const std::vector<std::string>& sets = {}) {
  std::vector<io::ConfigOverride> overrides;
  for (const std::string& set : sets) overrides.push_back(io::ParseOverride(set));
  return LoadScenario(kSource / "scenarios/small.yaml", overrides);
}

std::uint64_t HashPoses(const std::vector<core::Pose2>& poses, std::uint64_t h) {
  for (const core::Pose2& p : poses) {
    const double values[] = {p.x, p.y, p.theta};
    h = core::HashBytes(values, sizeof values, h);
  }
  return h;
}

// A hash of everything a mode's teach holds: the maps' grids (log-odds), paths and switch
// poses, the per-map traces, the match counts and the online switches.
std::uint64_t TeachHash(const ModeTeach& teach) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const nav::PartialMap& map : teach.bundle.maps) {
    const double header[] = {static_cast<double>(map.grid.width()),
                             static_cast<double>(map.grid.height()), map.grid.resolution(),
                             map.grid.origin().x(), map.grid.origin().y()};
    h = core::HashBytes(header, sizeof header, h);
    const std::vector<float>& cells = map.grid.log_odds();
    h = core::HashBytes(cells.data(), cells.size() * sizeof(float), h);
    h = HashPoses(map.path.poses(), h);
    h = HashPoses({map.X_MS}, h);
  }
  for (const TeachMapTrace& map : teach.trace.maps) {
    h = core::HashBytes(map.time.data(), map.time.size() * sizeof(double), h);
    h = HashPoses(map.X_MR, h);
    h = HashPoses(map.X_WR, h);
  }
  h = core::HashBytes(teach.match_counts.data(), sizeof teach.match_counts, h);
  for (const nav::OnlineSwitch& s : teach.online_switches) {
    const double values[] = {s.travelled, s.constraint, static_cast<double>(s.reason)};
    h = core::HashBytes(values, sizeof values, h);
  }
  return h;
}

void ExpectSameTeach(const TeachResult& serial, const TeachResult& parallel) {
  EXPECT_EQ(parallel.duration_s, serial.duration_s);
  EXPECT_EQ(parallel.events, serial.events);
  EXPECT_EQ(parallel.collisions.size(), serial.collisions.size());
  ASSERT_EQ(parallel.modes.size(), serial.modes.size());
  for (std::size_t m = 0; m < serial.modes.size(); ++m) {
    EXPECT_EQ(parallel.modes[m].mode, serial.modes[m].mode);
    EXPECT_EQ(parallel.modes[m].bundle.maps.size(), serial.modes[m].bundle.maps.size());
    EXPECT_EQ(TeachHash(parallel.modes[m]), TeachHash(serial.modes[m]))
        << "mode " << core::EnumName(serial.modes[m].mode);
  }
}

TEST(ParallelTeach, AnyThreadCountGivesTheBundlesOfOneThread) {
  const Scenario scenario = ParallelTeachScenario();
  const std::vector<MapMode> modes = {MapMode::kPartial, MapMode::kSingle, MapMode::kConsistent,
                                      MapMode::kScanMatched};
  const TeachResult serial = RunTeachDrive(scenario, modes, {}, nullptr, 1);
  ASSERT_GT(serial.modes.front().bundle.maps.size(), 1u);  // the switch signal is exercised
  for (int threads : {2, 3, 4, 8}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    ExpectSameTeach(serial, RunTeachDrive(scenario, modes, {}, nullptr, threads));
  }
}

TEST(ParallelTeach, OnlineSwitchingDecidesTheSameOnHelpers) {
  const Scenario scenario = ParallelTeachScenario({"route.switch_points=online"});
  const std::vector<MapMode> modes = {MapMode::kConsistent, MapMode::kPartial,
                                      MapMode::kScanMatched};
  const TeachResult serial = RunTeachDrive(scenario, modes, {}, nullptr, 1);
  ExpectSameTeach(serial, RunTeachDrive(scenario, modes, {}, nullptr, 3));
}

TEST(ParallelTeach, ATeacherThatTimesOutStillThrowsWithHelpers) {
  const Scenario scenario = ParallelTeachScenario({"teach.timeout_s=5"});
  EXPECT_THROW(RunTeachDrive(scenario, {MapMode::kPartial, MapMode::kSingle}, {}, nullptr, 2),
               core::WorldError);
}

}  // namespace parallel_teach_test
}  // namespace retrace::bench
