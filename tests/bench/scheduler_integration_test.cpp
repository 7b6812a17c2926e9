// The one scheduler (bench/engine/scheduler.hpp) on the small scenario: a failing job's error
// names it, and of several failures the first in the queue's order wins; a cancelled sink stops
// every episode. (The same runs on any number of threads: scheduler_system_test.cpp.)

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <string>
#include <vector>

#include "bench/engine/scenario.hpp"
#include "bench/engine/scheduler.hpp"
#include "bench/engine/teach_drive.hpp"
#include "core/errors.hpp"
#include "tests/support/source_dir.hpp"

namespace retrace::bench {
namespace scheduler_test {  // not anonymous: unity builds batch test files together

using retrace::testing::kSource;

Scenario SchedulerScenario() { return LoadScenario(kSource / "scenarios/small.yaml", {}); }

// Two jobs whose loading fails: the error names the first in the queue's order (drives of
// unknown routes keep the jobs' order), on one thread or two.
TEST(Scheduler, TheFirstFailingJobInTheQueuesOrderIsReportedByName) {
  for (const int threads : {1, 2}) {
    std::vector<EpisodeJob> jobs(2);
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      jobs[j].name = "case " + std::to_string(j);
      jobs[j].modes = {MapMode::kPartial};
      jobs[j].repeats = 1;
      jobs[j].load = [j]() -> const Scenario* {
        throw core::ConfigError("nav.localizer.particles", "bad in job " + std::to_string(j));
      };
    }
    try {
      RunEpisodes(std::move(jobs), threads, nullptr, {});
      ADD_FAILURE() << "no error with " << threads << " threads";
    } catch (const core::Error& e) {
      EXPECT_STREQ(e.what(), "case 0: nav.localizer.particles: bad in job 0");
    }
  }
}

// A sink that asks to stop once `after_s` simulated seconds were reported (the Python module's
// on Ctrl-C), and counts the units done.
class StoppingSink : public ProgressSink {
 public:
  explicit StoppingSink(double after_s) : after_s_(after_s) {}
  void Phase(const std::string&, int) override {}
  void AddSimTime(double seconds) override {
    std::lock_guard lock(mutex_);
    sim_time_s_ += seconds;
  }
  void UnitDone() override { ++units_; }
  bool Cancelled() const override {
    std::lock_guard lock(mutex_);
    return sim_time_s_ >= after_s_;
  }
  int units() const { return units_; }

 private:
  double after_s_;
  mutable std::mutex mutex_;
  double sim_time_s_ = 0.0;
  std::atomic<int> units_{0};
};

// Stopping ends every episode at its next report with core::Interrupted, which no job's name
// wraps (it is no core::Error): the drives of four named jobs stop before any is done.
TEST(Scheduler, ACancelledSinkStopsEveryEpisodeWithInterrupted) {
  const Scenario scenario = SchedulerScenario();
  for (const int threads : {1, 2}) {
    std::vector<EpisodeJob> jobs(4);
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      jobs[j].name = "case " + std::to_string(j);
      jobs[j].scenario = &scenario;
      jobs[j].modes = {MapMode::kPartial};
      jobs[j].repeats = 2;
    }
    StoppingSink sink(/*after_s=*/15.0);
    EXPECT_THROW(RunEpisodes(std::move(jobs), threads, &sink, {}), core::Interrupted) << threads;
    EXPECT_EQ(sink.units(), 0) << threads;  // a drive takes 92 s simulated
  }
}

}  // namespace scheduler_test
}  // namespace retrace::bench
