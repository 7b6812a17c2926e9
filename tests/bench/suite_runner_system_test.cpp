// A suite's numbers are `retrace run`'s numbers: per seed, the aggregate metrics of the same
// teaching drive and playback runs, whatever the number of threads; the suite value is their
// mean. Runs one lap of the small test room (two seeds, one run each) to stay short.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "bench/metrics/experiment.hpp"
#include "bench/metrics/flat_metrics.hpp"
#include "bench/suite/suite_runner.hpp"
#include "bench/suite/suite_spec.hpp"
#include "core/errors.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
namespace {

using ::testing::HasSubstr;
using SuiteRunnerTest = retrace::testing::TempDirTest;

using retrace::testing::kSource;

constexpr const char* kOneLap =
    "{route.points: [[1, 1], [9, 1], [9, 5], [1, 5]], route.switch_points: [10]}";

SuiteSpec OneLapSuite(const retrace::testing::TempDir& tmp) {
  const std::string small =
      std::filesystem::relative(kSource / "scenarios/small.yaml", tmp.path()).string();
  return LoadSuiteSpec(tmp.Write("suite.yaml",
                                 "name: lap\n"
                                 "entries:\n"
                                 "  - {scenario: " +
                                     small +
                                     ", modes: [partial], seeds: [1, 2], repeats: 1,\n"
                                     "     set: " +
                                     kOneLap +
                                     "}\n"
                                     "metrics:\n"
                                     "  \"*.*.success_rate\": {abs: 0}\n"));
}

void ExpectSameNavigationMetrics(const std::map<std::string, double>& a,
                                 const std::map<std::string, double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [name, value] : a) {
    if (IsTimingMetric(name)) continue;
    ASSERT_EQ(b.count(name), 1u) << name;
    if (std::isnan(value)) {
      EXPECT_TRUE(std::isnan(b.at(name))) << name;
    } else {
      EXPECT_EQ(value, b.at(name)) << name;
    }
  }
}

TEST_F(SuiteRunnerTest, SameNumbersAsRetraceRunForEachSeedWhateverTheThreads) {
  const SuiteSpec spec = OneLapSuite(tmp_);
  const SuiteScenarios scenarios = LoadSuiteScenarios(spec, {});
  ASSERT_EQ(scenarios.scenarios.size(), 1u);
  ASSERT_EQ(scenarios.scenarios[0].size(), 2u);
  EXPECT_EQ(scenarios.scenarios[0][1].config.seed, 2u);
  EXPECT_EQ(scenarios.scenarios[0][1].config.playback.repeats, 1);
  EXPECT_EQ(scenarios.scenarios[0][1].config.modes, std::vector<MapMode>{MapMode::kPartial});

  const SuiteResults parallel = RunSuite(spec, scenarios, 2);
  EXPECT_EQ(parallel.teaching_drives, 2);
  EXPECT_EQ(parallel.playback_runs, 2);
  ASSERT_EQ(parallel.metrics.size(), AggregateMetricNames().size());

  // `retrace run --seed S --repeats 1 --mode partial` of the same scenario, in this thread.
  for (std::size_t s = 0; s < 2; ++s) {
    std::vector<io::ConfigOverride> overrides = spec.entries[0].overrides;
    overrides.push_back({"seed", std::to_string(s + 1)});
    overrides.push_back({"playback.repeats", "1"});
    const Scenario scenario = LoadScenario(kSource / "scenarios/small.yaml", overrides);
    ExperimentOptions options;
    options.repeats = 1;
    const Experiment experiment = RunExperiment(scenario, {MapMode::kPartial}, options);
    std::map<std::string, double> suite_seed;
    for (const auto& [name, metric] : parallel.metrics)
      suite_seed[name.substr(std::string("small.partial.").size())] = metric.per_seed[s];
    ExpectSameNavigationMetrics(FlatMetrics(experiment.modes[0].aggregate), suite_seed);
  }

  const SuiteMetric& progress = parallel.metrics.at("small.partial.mean_progress_m");
  EXPECT_GT(progress.per_seed[0], 15.0);  // a 20 m lap
  EXPECT_DOUBLE_EQ(progress.mean, (progress.per_seed[0] + progress.per_seed[1]) / 2.0);
}

TEST_F(SuiteRunnerTest, BadOverridesAreErrorsBeforeAnythingRuns) {
  const std::string small =
      std::filesystem::relative(kSource / "scenarios/small.yaml", tmp_.path()).string();
  const SuiteSpec spec = LoadSuiteSpec(tmp_.Write("suite.yaml",
                                                  "name: t\n"
                                                  "entries:\n"
                                                  "  - {scenario: " +
                                                      small +
                                                      ", modes: [partial], seeds: [1],\n"
                                                      "     set: {nav.localizer.particle: 10}}\n"
                                                      "metrics:\n"
                                                      "  \"*.*.success_rate\": {abs: 0}\n"));
  try {
    LoadSuiteScenarios(spec, {});
    FAIL() << "no error";
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("suite.yaml:3: entry 'small': "));
    EXPECT_THAT(e.what(),
                HasSubstr("nav.localizer.particle: unknown key; did you mean 'particles'?"));
  }
  try {
    LoadSuiteScenarios(OneLapSuite(tmp_), {io::ParseOverride("playback.repeats=5")});
    FAIL() << "no error";
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(
        e.what(),
        HasSubstr("cannot set playback.repeats: a suite entry's `seeds` and `repeats` decide it"));
  }
  try {
    LoadSuiteScenarios(OneLapSuite(tmp_), {io::ParseOverride("nav.follower.max_sped=1")});
    FAIL() << "no error";
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("max_sped: unknown key"));
  }
}

}  // namespace
}  // namespace retrace::bench
