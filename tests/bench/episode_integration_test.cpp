// Teach → playback end to end on the small scenario: success, plausible metrics, determinism,
// and the failure the paper predicts when a map's segment revisits itself. (The whole `retrace
// run` command: run_command_system_test.cpp.)

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bench/engine/playback.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/metrics/metrics.hpp"
#include "core/rng.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/trajectory_hash.hpp"

namespace retrace::bench {
namespace {

using testing::TrajectoryHash;

using retrace::testing::kSource;

Scenario Small(std::vector<std::string> sets = {}) {
  std::vector<io::ConfigOverride> overrides;
  for (const std::string& s : sets) overrides.push_back(io::ParseOverride(s));
  return LoadScenario(kSource / "scenarios/small.yaml", overrides);
}

// The teaching drive of the small scenario in partial mode, shared by the tests below.
const ModeTeach& PartialTeach() {
  static const ModeTeach teach = [] {
    TeachResult result = RunTeachDrive(Small(), {MapMode::kPartial});
    return std::move(result.modes.front());
  }();
  return teach;
}

TEST(Episode, SmallScenarioPlaybackSucceedsWithPlausibleMetrics) {
  const Scenario scenario = Small();
  const ModeTeach& teach = PartialTeach();
  ASSERT_EQ(teach.bundle.maps.size(), 2u);  // one switch point
  ASSERT_EQ(teach.trace.maps.size(), 2u);
  const RunTrace run = RunPlayback(scenario, teach.bundle, teach.trace, 0, 300.0);
  EXPECT_EQ(run.outcome, Outcome::kSuccess);
  ASSERT_EQ(run.switches.size(), 1u);
  const RunMetrics m = ComputeRunMetrics(teach.trace, run, scenario.config.metrics);
  EXPECT_TRUE(m.success);
  EXPECT_LT(m.tracking_error_m.rms, 0.25);
  EXPECT_LT(m.tracking_error_m.max, 0.8);
  EXPECT_LT(m.localization_error_m.rms, 0.25);
  EXPECT_LT(m.switch_error_max_m, 0.5);
  EXPECT_NEAR(m.path_length_m, scenario.route_length, 0.1 * scenario.route_length);
  EXPECT_EQ(m.collisions.pedestrian_incidents, 0);
  // Timings are recorded (their values are never asserted: machines vary), consistently: the
  // run's CPU time holds its localizer updates', and the real-time factor is the ratio.
  EXPECT_EQ(m.cpu.localizer_updates, static_cast<int>(run.updates.size()));
  EXPECT_GT(m.cpu.localizer_updates, 0);
  EXPECT_GE(m.cpu.cpu_time_s, 1e-3 * m.cpu.localizer_update_mean_ms * m.cpu.localizer_updates);
  EXPECT_DOUBLE_EQ(m.cpu.real_time_factor, m.cpu.sim_time_s / m.cpu.cpu_time_s);
  EXPECT_GT(m.dynamic_points.beams_tested, 0);

  // The snapshot for the figures: the update with the most pedestrian beams.
  ASSERT_TRUE(run.snapshot.has_value());
  const LocalizationSnapshot& snap = *run.snapshot;
  EXPECT_GT(snap.pedestrian_beams, 0);
  EXPECT_EQ(snap.particles.size(),
            static_cast<std::size_t>(scenario.config.nav.localizer.particles));
  EXPECT_EQ(snap.beam_use.size(), snap.scan.size());
  EXPECT_EQ(snap.likelihood.size, 81);
  EXPECT_EQ(snap.likelihood.all_beams.size(), 81u * 81u);
  EXPECT_LT((snap.X_MR_estimate.translation() - snap.X_MR_truth.translation()).norm(), 0.5);
}

TEST(Episode, SameSeedSameTrajectoryOtherRunOtherTrajectory) {
  const Scenario scenario = Small();
  const ModeTeach& teach = PartialTeach();
  const RunTrace a = RunPlayback(scenario, teach.bundle, teach.trace, 0, 60.0);
  const RunTrace b = RunPlayback(scenario, teach.bundle, teach.trace, 0, 60.0);
  const RunTrace c = RunPlayback(scenario, teach.bundle, teach.trace, 1, 60.0);
  EXPECT_EQ(TrajectoryHash(a), TrajectoryHash(b));
  EXPECT_NE(TrajectoryHash(a), TrajectoryHash(c));
  const TeachResult again = RunTeachDrive(scenario, {MapMode::kPartial});
  EXPECT_EQ(again.modes.front().trace.X_WR.back(), teach.trace.X_WR.back());
}

// The paper's warning: a map whose segment revisits a place holds that place twice, shifted by
// the odometry drift in between, and localization in it fails. With strong drift (3 % scale
// error, 0.3 % wheel-radius mismatch) one map of both laps (mode single, i.e. no switch before
// the revisit) loses the robot, while the partial maps of the same drive still work.
TEST(Episode, ASegmentThatRevisitsItselfFailsAsThePaperPredicts) {
  const Scenario scenario =
      Small({"sim.odometry.scale_error=0.03", "sim.odometry.radius_mismatch=0.003"});
  const TeachResult teach = RunTeachDrive(scenario, {MapMode::kPartial, MapMode::kSingle});
  const ModeTeach& partial = teach.modes[0];
  const ModeTeach& single = teach.modes[1];
  ASSERT_EQ(single.bundle.maps.size(), 1u);
  // With this much drift partial maps succeed in about 3 runs of 4 (17 and 18 of 24 over 12
  // seeds, 2026-11-26), the single map in none: the first of two partial-map runs that succeeds.
  const RunTrace first = RunPlayback(scenario, partial.bundle, partial.trace, 0, 300.0);
  const RunTrace good = first.outcome == Outcome::kSuccess
                            ? first
                            : RunPlayback(scenario, partial.bundle, partial.trace, 1, 300.0);
  const RunTrace bad = RunPlayback(scenario, single.bundle, single.trace, 0, 300.0);
  EXPECT_EQ(good.outcome, Outcome::kSuccess) << "neither of two partial-map runs succeeded";
  EXPECT_NE(bad.outcome, Outcome::kSuccess);
  const RunMetrics g = ComputeRunMetrics(partial.trace, good, scenario.config.metrics);
  const RunMetrics b = ComputeRunMetrics(single.trace, bad, scenario.config.metrics);
  EXPECT_GT(b.localization_error_m.rms, 2.0 * g.localization_error_m.rms);
  EXPECT_LT(b.progress_m, 0.9 * scenario.route_length);
}

TEST(Scenarios, EveryShippedScenarioLoadsAndValidates) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kSource / "scenarios")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const Scenario scenario = LoadScenario(entry.path());
    EXPECT_GT(scenario.route_length, 10.0);
    EXPECT_TRUE(scenario.warnings.empty()) << scenario.warnings.front();
    ++count;
  }
  EXPECT_GE(count, 3);
}

TEST(Scenarios, EveryShippedWorldLoads) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kSource / "worlds")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(sim::LoadWorld(entry.path()));
    ++count;
  }
  EXPECT_GE(count, 3);
}

}  // namespace
}  // namespace retrace::bench
