// The one scheduler (bench/engine/scheduler.hpp) on the small scenario: jobs given a scenario,
// jobs that load theirs and jobs given their teach give the same runs whatever the number of
// threads; every (job, mode) is handed over once, after its last run (system tier: seven teaching
// drives and six playback runs, 22 s under the sanitizers).
#include <gtest/gtest.h>

#include <atomic>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "bench/engine/scenario.hpp"
#include "bench/engine/scheduler.hpp"
#include "bench/engine/teach_drive.hpp"
#include "io/config_override.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/trajectory_hash.hpp"

namespace retrace::bench {
namespace scheduler_system_test {  // not anonymous: unity builds batch test files together

using retrace::testing::kSource;
using retrace::testing::TrajectoryHash;

struct MixedOutcome {
  std::map<std::tuple<std::size_t, std::size_t, int>, std::uint64_t> runs;  // hash per run
  std::map<std::pair<std::size_t, std::size_t>, int> handed_over;           // mode_done calls
  bool handed_over_after_runs = true;
  int loads = 0;
};

// Job 0 is given its scenario (1 run of partial), job 1 loads a scenario of another seed
// (1 run), job 2 is given job 0's teach read back (1 run), job 3 only teaches.
MixedOutcome RunMixedJobs(int threads) {
  static const Scenario given = LoadScenario(kSource / "scenarios/small.yaml", {});
  static const TeachResult taught = RunTeachDrive(given, {MapMode::kPartial});
  std::optional<Scenario> loaded;
  std::atomic<int> loads{0};
  std::vector<EpisodeJob> jobs(4);
  jobs[0].scenario = &given;
  jobs[0].modes = {MapMode::kPartial};
  jobs[0].repeats = 1;
  jobs[1].load = [&]() -> const Scenario* {
    ++loads;
    return &loaded.emplace(
        LoadScenario(kSource / "scenarios/small.yaml", {io::ParseOverride("seed=7")}));
  };
  jobs[1].modes = {MapMode::kPartial};
  jobs[1].repeats = 1;
  jobs[2].scenario = &given;
  jobs[2].taught = {taught.modes.front()};
  jobs[2].taught_duration_s = taught.duration_s;
  jobs[2].repeats = 1;
  jobs[3].scenario = &given;
  jobs[3].modes = {MapMode::kSingle, MapMode::kPartial};

  MixedOutcome out;
  std::mutex mutex;
  EpisodeCallbacks callbacks;
  callbacks.run_done = [&](std::size_t j, std::size_t m, const ModeTeach&, RunTrace&& run) {
    std::lock_guard lock(mutex);
    out.runs[{j, m, run.run}] = TrajectoryHash(run);
    if (out.handed_over.contains({j, m})) out.handed_over_after_runs = false;
  };
  callbacks.mode_done = [&](std::size_t j, std::size_t m, ModeTeach&& teach) {
    std::lock_guard lock(mutex);
    ++out.handed_over[{j, m}];
    EXPECT_FALSE(teach.bundle.maps.empty());
  };
  RunEpisodes(std::move(jobs), threads, nullptr, callbacks);
  out.loads = loads;
  return out;
}

TEST(Scheduler, MixedJobsGiveTheSameRunsOnOneOrThreeThreads) {
  const MixedOutcome one = RunMixedJobs(1);
  const MixedOutcome three = RunMixedJobs(3);
  EXPECT_EQ(one.runs.size(), 3u);
  EXPECT_EQ(one.runs, three.runs);
  // Job 2 plays back job 0's teach with run index 0, as job 0's first run does.
  EXPECT_EQ(one.runs.at({2, 0, 0}), one.runs.at({0, 0, 0}));
  // A scenario of another seed gives another run.
  EXPECT_NE(one.runs.at({1, 0, 0}), one.runs.at({0, 0, 0}));
  for (const MixedOutcome* o : {&one, &three}) {
    EXPECT_EQ(o->loads, 1);
    EXPECT_TRUE(o->handed_over_after_runs);
    const std::map<std::pair<std::size_t, std::size_t>, int> once = {
        {{0, 0}, 1}, {{1, 0}, 1}, {{2, 0}, 1}, {{3, 0}, 1}, {{3, 1}, 1}};
    EXPECT_EQ(o->handed_over, once);
  }
}

}  // namespace scheduler_system_test
}  // namespace retrace::bench
