// Teach → playback end to end on the small scenario: success, plausible metrics, determinism,
// the files written, and the failure the paper predicts when a map's segment revisits itself.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bench/cli/run_command.hpp"
#include "bench/engine/playback.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/metrics/metrics.hpp"
#include "bench/output/render_results.hpp"
#include "bench/output/results_io.hpp"
#include "core/rng.hpp"
#include "io/json_writer.hpp"
#include "io/tum.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/temp_dir.hpp"
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
  EXPECT_GT(m.cpu.localizer_updates, 0);  // timings are recorded (never asserted: machines vary)
  EXPECT_GT(m.cpu.cpu_time_s, 0.0);
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

// `retrace run scenarios/small.yaml --mode <mode> --repeats 1 --out <out> --jobs <jobs>`.
RunOptions SmallRun(const std::string& mode, const std::filesystem::path& out, int jobs) {
  RunOptions options;
  options.scenario = kSource / "scenarios/small.yaml";
  options.modes = {mode};
  options.repeats = 1;
  options.out = out;
  options.jobs = jobs;
  return options;
}

TEST(Episode, RunCommandWritesFilesThatParseBack) {
  const retrace::testing::TempDir tmp;
  const RunOptions options = SmallRun("partial", tmp.path() / "small", 1);
  EXPECT_EQ(RunRunCommand(options, RunPhases::kAll, "retrace run (test)"), 0);
  const std::filesystem::path dir = options.out / "partial";
  const nlohmann::json metrics = io::ReadJsonFile(dir / "metrics.json");
  EXPECT_EQ(metrics["mode"], "partial");
  EXPECT_EQ(metrics["runs"].size(), 1u);
  EXPECT_TRUE(metrics["aggregate"].contains("success_rate"));
  EXPECT_TRUE(std::filesystem::exists(dir / "manifest.yaml"));
  const auto gt = io::ReadTum(dir / "runs/0/gt.tum");
  const auto est = io::ReadTum(dir / "runs/0/est.tum");
  EXPECT_EQ(gt.size(), est.size());
  EXPECT_GT(gt.size(), 100u);
  const ModeTeach reread = ReadTeachFolder(dir / "teach", MapMode::kPartial);
  EXPECT_EQ(reread.bundle.maps.size(), 2u);
  EXPECT_EQ(reread.trace.maps.size(), 2u);
  EXPECT_FALSE(std::filesystem::exists(options.out / "partial.tmp"));
  const RunTrace reread_run = ReadRunFolder(dir / "runs/0", 0);
  ASSERT_EQ(reread_run.samples.size(), gt.size());
  EXPECT_EQ(reread_run.samples.back().X_WR, gt.back().pose);
  EXPECT_EQ(reread_run.samples.back().map_index, 1);
  for (const char* figure : {"maps.png", "playback_partial.png", "odometry.png", "errors.png",
                             "snapshot.png", "likelihood.png"}) {
    EXPECT_GT(std::filesystem::file_size(dir / "figures" / figure), 10000u) << figure;
  }
  // `retrace render`: the figures again, from the files alone.
  std::filesystem::remove(dir / "figures/playback_partial.png");
  EXPECT_FALSE(RenderResults(options.out).empty());
  EXPECT_GT(std::filesystem::file_size(dir / "figures/playback_partial.png"), 10000u);

  // Playback again from the written teach folder.
  RunOptions again = options;
  again.teach_dir = dir / "teach";
  again.out = tmp.path() / "again";
  EXPECT_EQ(RunRunCommand(again, RunPhases::kPlaybackOnly, "retrace playback (test)"), 0);
  EXPECT_TRUE(std::filesystem::exists(again.out / "partial/runs/0/gt.tum"));
}

// The paper's warning: a map whose segment revisits a place holds that place twice, shifted by
// the odometry drift in between, and localization in it fails. With strong drift (3 % scale
// error, 0.3 % wheel-radius mismatch) one map of both laps (mode single, i.e. no switch before
// the revisit) loses the robot, while the partial maps of the same drive still work.
// Figures come last: when they cannot be written the numbers stay, with a warning and exit 0.
TEST(Episode, AFigureFailureLeavesTheResultsAndTheExitCode) {
  const retrace::testing::TempDir tmp;
  const RunOptions options = SmallRun("partial", tmp.path() / "small", 1);
  std::filesystem::create_directories(options.out);
  { std::ofstream(options.out / "figures") << "a file where the figures folder goes\n"; }
  ::testing::internal::CaptureStderr();
  const int code = RunRunCommand(options, RunPhases::kAll, "retrace run (test)");
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(code, 0);
  EXPECT_NE(err.find("warning: no figures"), std::string::npos) << err;
  EXPECT_TRUE(std::filesystem::exists(options.out / "partial/metrics.json"));
  EXPECT_TRUE(std::filesystem::exists(options.out / "partial/runs/0/gt.tum"));
}

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
