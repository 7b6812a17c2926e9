// The playback loop talks to the navigation stack only through NavigationStack: a stack that
// wraps retrace's and offers nothing but the interface drives exactly the run RunPlayback
// drives (the odometry baseline: odometry_baseline_system_test.cpp).

#include <gtest/gtest.h>

#include "bench/engine/playback.hpp"
#include "bench/engine/playback_episode.hpp"
#include "bench/engine/retrace_stack.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/metrics/metrics.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/trajectory_hash.hpp"

namespace retrace::bench {
namespace {

Scenario SmallScenario() {
  return LoadScenario(retrace::testing::kSource / "scenarios/small.yaml", {});
}

const ModeTeach& SmallPartialTeach() {
  static const ModeTeach teach = [] {
    TeachResult result = RunTeachDrive(SmallScenario(), {MapMode::kPartial});
    return std::move(result.modes.front());
  }();
  return teach;
}

// A third party's stack, as the loop sees it: it hides that retrace's navigator is inside.
class OpaqueStack final : public NavigationStack {
 public:
  explicit OpaqueStack(NavigationStack& inner) : inner_(inner) {}
  void OnOdometry(double t, const core::OdometryDelta& d) override { inner_.OnOdometry(t, d); }
  void OnScan(const core::LaserScan& scan) override {
    ++scans;
    inner_.OnScan(scan);
  }
  StackOutput OnControlTick(double t, double dt) override {
    ++ticks;
    return inner_.OnControlTick(t, dt);
  }
  int scans = 0;
  int ticks = 0;

 private:
  NavigationStack& inner_;
};

TEST(NavigationStack, AStackSeenOnlyThroughTheInterfaceDrivesRunPlaybacksRun) {
  const Scenario scenario = SmallScenario();
  const ModeTeach& teach = SmallPartialTeach();
  const RunTrace reference = RunPlayback(scenario, teach.bundle, teach.trace, 0, 300.0);

  RetraceStack inner(scenario, teach.bundle, PlaybackRng(scenario.config, 0));
  OpaqueStack stack(inner);
  PlaybackEpisode episode(scenario, teach.bundle, teach.trace, 0, 300.0, stack);
  do {
    episode.Sense();
  } while (!episode.Act());
  const RunTrace run = episode.Finish();

  EXPECT_EQ(retrace::testing::TrajectoryHash(run), retrace::testing::TrajectoryHash(reference));
  EXPECT_EQ(run.outcome, reference.outcome);
  ASSERT_EQ(run.switches.size(), reference.switches.size());
  EXPECT_EQ(stack.ticks, static_cast<int>(run.samples.size()));
  EXPECT_GT(stack.scans, stack.ticks / 4);
  // Without retrace's localizer in sight, no update is scored; everything else is measured.
  EXPECT_TRUE(run.updates.empty());
  EXPECT_FALSE(reference.updates.empty());
  const RunMetrics a = ComputeRunMetrics(teach.trace, run, scenario.config.metrics);
  const RunMetrics b = ComputeRunMetrics(teach.trace, reference, scenario.config.metrics);
  EXPECT_EQ(a.success, b.success);
  EXPECT_DOUBLE_EQ(a.tracking_error_m.rms, b.tracking_error_m.rms);
  EXPECT_DOUBLE_EQ(a.localization_error_m.max, b.localization_error_m.max);
}

}  // namespace
}  // namespace retrace::bench
