// Suite files: what a well-formed suite reads as, the metric names it yields, and one clear
// located error for each way a suite can be wrong.

#include "bench/suite/suite_spec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "core/errors.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
namespace {

using ::testing::HasSubstr;
using SuiteSpecTest = retrace::testing::TempDirTest;

using retrace::testing::kSource;

// The small scenario as a path relative to the suite's folder, as suites write it.
std::string SmallFrom(const std::filesystem::path& dir) {
  return std::filesystem::relative(kSource / "scenarios/small.yaml", dir).string();
}

// The ConfigError message of loading `text` as a suite ("" when it loads).
std::string LoadError(const retrace::testing::TempDir& tmp, const std::string& text) {
  try {
    LoadSuiteSpec(tmp.Write("suite.yaml", text));
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

// A valid suite around `metrics` (YAML lines of the metrics mapping).
std::string Suite(const retrace::testing::TempDir& tmp, const std::string& metrics,
                  const std::string& entry_extra = "") {
  return "name: t\nentries:\n  - scenario: " + SmallFrom(tmp.path()) +
         "\n    modes: [partial, single]\n    seeds: [1]\n" + entry_extra + "metrics:\n" + metrics;
}

TEST_F(SuiteSpecTest, ReadsEntriesSeedsOverridesAndRules) {
  const std::string small = SmallFrom(tmp_.path());
  const SuiteSpec spec = LoadSuiteSpec(
      tmp_.Write("s.yaml",
                 "name: ci\n"
                 "entries:\n"
                 "  - scenario: " +
                     small +
                     "\n"
                     "    modes: [partial, single, consistent]\n"
                     "    seeds: [1, 2, 3]\n"
                     "  - scenario: " +
                     small +
                     "\n"
                     "    name: small_fast\n"
                     "    modes: [partial]\n"
                     "    seeds: [7]\n"
                     "    repeats: 3\n"
                     "    set: {nav.localizer.particles: 300, route.switch_points: [10, 20]}\n"
                     "metrics:\n"
                     "  \"*.partial.success_rate\": {min: 1.0}\n"
                     "  \"*.*.tracking_error_m.pooled.rms\": {abs: 0.02, max: 0.5}\n"
                     "  \"*.*.localization_error_m.pooled.rms\": {rel: 0.25, better: lower}\n"
                     "  \"*.*.cpu.real_time_factor\": {report: true}\n"));
  EXPECT_EQ(spec.name, "ci");
  EXPECT_EQ(spec.digest.rfind("fnv1a64:", 0), 0u);
  EXPECT_EQ(spec.digest.size(), 8u + 16u);
  ASSERT_EQ(spec.entries.size(), 2u);

  const SuiteEntry& first = spec.entries[0];
  EXPECT_EQ(first.name, "small");  // the scenario's own name
  EXPECT_EQ(first.scenario_text, small);
  EXPECT_TRUE(std::filesystem::equivalent(first.scenario, kSource / "scenarios/small.yaml"));
  EXPECT_EQ(first.modes,
            (std::vector<MapMode>{MapMode::kPartial, MapMode::kSingle, MapMode::kConsistent}));
  EXPECT_EQ(first.seeds, (std::vector<std::uint64_t>{1, 2, 3}));
  EXPECT_EQ(first.repeats, 2);  // the default
  EXPECT_TRUE(first.overrides.empty());
  EXPECT_EQ(first.line, 3);

  const SuiteEntry& second = spec.entries[1];
  EXPECT_EQ(second.name, "small_fast");
  EXPECT_EQ(second.repeats, 3);
  ASSERT_EQ(second.overrides.size(), 2u);
  EXPECT_EQ(second.overrides[0].key_path, "nav.localizer.particles");
  EXPECT_EQ(second.overrides[0].value, "300");
  EXPECT_EQ(second.overrides[1].key_path, "route.switch_points");
  EXPECT_EQ(second.overrides[1].value, "[10, 20]");

  ASSERT_EQ(spec.rules.size(), 4u);
  EXPECT_EQ(spec.rules[0].pattern, "*.partial.success_rate");
  EXPECT_EQ(spec.rules[0].tolerance.min, 1.0);
  EXPECT_FALSE(spec.rules[0].tolerance.has_delta());
  EXPECT_EQ(spec.rules[1].tolerance.abs, 0.02);
  EXPECT_EQ(spec.rules[1].tolerance.max, 0.5);
  EXPECT_EQ(spec.rules[2].tolerance.rel, 0.25);
  EXPECT_EQ(spec.rules[2].tolerance.better, Better::kLower);
  EXPECT_TRUE(spec.rules[3].tolerance.report);
  EXPECT_EQ(spec.rules[3].line, 16);
}

TEST_F(SuiteSpecTest, MetricNamesAreEntryModeAndAggregateMetric) {
  const SuiteSpec spec =
      LoadSuiteSpec(tmp_.Write("s.yaml", Suite(tmp_, "  \"*.*.success_rate\": {abs: 0}\n")));
  const std::vector<std::string> names = SuiteMetricNames(spec);
  const std::size_t per_mode = AggregateMetricNames().size();
  ASSERT_EQ(names.size(), 2 * per_mode);
  for (const char* metric :
       {"success_rate", "tracking_error_m.pooled.rms", "localization_error_m.pooled.rms",
        "repeatability_m", "switch_error.max_m", "collisions.pedestrian_incidents",
        "cpu.real_time_factor", "outcomes.lost", "dynamic_points.recall"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), std::string("small.partial.") + metric),
              names.end())
        << metric;
    EXPECT_NE(std::find(names.begin(), names.end(), std::string("small.single.") + metric),
              names.end())
        << metric;
  }
  EXPECT_EQ(names.front().rfind("small.partial.", 0), 0u);  // entry, then mode in the suite's order
  EXPECT_EQ(names.back().rfind("small.single.", 0), 0u);
}

TEST(SuiteMetricName, SplitsAtTheFirstTwoDots) {
  const SuiteMetricName name = SplitSuiteMetricName("office.partial.tracking_error_m.pooled.rms");
  EXPECT_EQ(name.entry, "office");
  EXPECT_EQ(name.mode, "partial");
  EXPECT_EQ(name.metric, "tracking_error_m.pooled.rms");
  EXPECT_EQ(SplitSuiteMetricName("small.single.success_rate").metric, "success_rate");
  // Fewer than two dots: no entry and mode, all metric.
  EXPECT_EQ(SplitSuiteMetricName("maps").metric, "maps");
  EXPECT_EQ(SplitSuiteMetricName("a.b").metric, "a.b");
  EXPECT_EQ(SplitSuiteMetricName("a.b").entry, "");
}

TEST_F(SuiteSpecTest, OnlySelectsEntriesAndModesInTheSuitesOrder) {
  const std::string small = SmallFrom(tmp_.path());
  const SuiteSpec spec = LoadSuiteSpec(tmp_.Write(
      "s.yaml", "name: t\nentries:\n  - scenario: " + small +
                    "\n    modes: [partial, single, consistent]\n    seeds: [1]\n  - scenario: " +
                    small + "\n    name: other\n    modes: [partial, single]\n    seeds: [2]\n"
                    "metrics:\n  \"*.*.success_rate\": {abs: 0}\n"));

  // Selectors in any order: the suite's order stays, a repeated selector counts once.
  const SuiteSpec some = SelectRuns(spec, {"small.consistent", "other", "small.partial", "other"});
  ASSERT_EQ(some.entries.size(), 2u);
  EXPECT_EQ(some.entries[0].name, "small");
  EXPECT_EQ(some.entries[0].modes, (std::vector<MapMode>{MapMode::kPartial, MapMode::kConsistent}));
  EXPECT_EQ(some.entries[0].seeds, spec.entries[0].seeds);
  EXPECT_EQ(some.entries[1].modes, spec.entries[1].modes);
  EXPECT_EQ(some.rules.size(), spec.rules.size());

  const SuiteSpec one = SelectRuns(spec, {"other.single"});
  ASSERT_EQ(one.entries.size(), 1u);
  EXPECT_EQ(one.entries[0].name, "other");
  EXPECT_EQ(one.entries[0].modes, std::vector<MapMode>{MapMode::kSingle});
  EXPECT_EQ(SuiteMetricNames(one).front().rfind("other.single.", 0), 0u);

  auto error = [&](const std::string& selector) {
    try {
      SelectRuns(spec, {selector});
    } catch (const core::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_THAT(error("office"), HasSubstr("no entry 'office' (entries: small, other)"));
  EXPECT_THAT(error("other.consistent"),
              HasSubstr("does not run mode 'consistent' (its modes: partial, single)"));
  EXPECT_THAT(error("small.parital"), HasSubstr("does not run mode 'parital'"));
  EXPECT_THAT(error(""), HasSubstr("no entry ''"));
}

TEST_F(SuiteSpecTest, ErrorsNameTheFileLineAndKey) {
  const std::string small = SmallFrom(tmp_.path());
  const std::string file = (tmp_.path() / "suite.yaml").string();
  EXPECT_THAT(LoadError(tmp_, "name: t\nentrys: []\n"),
              HasSubstr(file + ":2: entrys: unknown key; did you mean 'entries'?"));
  EXPECT_THAT(
      LoadError(tmp_, "name: t\nentries: [{scenario: x.yaml, modes: [partial], seeds: [1]}\n"),
      HasSubstr("invalid YAML"));
  EXPECT_THAT(LoadError(tmp_, "entries: []\nmetrics: {}\n"), HasSubstr("missing key 'name'"));
  EXPECT_THAT(LoadError(tmp_, "name: c.i\nentries: []\n"),
              HasSubstr("name: 'c.i' must be letters, digits, _ or -"));
  EXPECT_THAT(LoadError(tmp_, "name: t\nentries: []\nmetrics: {}\n"),
              HasSubstr("entries: expected a list of entries"));
  EXPECT_THAT(
      LoadError(tmp_,
                "name: t\nentries:\n  - {scenario: nowhere.yaml, modes: [partial], seeds: [1]}\n"),
      HasSubstr(":3: entries[0].scenario: no scenario file"));
  EXPECT_THAT(LoadError(tmp_, "name: t\nentries:\n  - {scenario: " + small + ", seeds: [1]}\n"),
              HasSubstr(":3: entries[0]: missing key 'modes'"));
  EXPECT_THAT(LoadError(tmp_, "name: t\nentries:\n  - {scenario: " + small +
                                  ", modes: [partial, fancy], seeds: [1]}\n"),
              HasSubstr("entries[0].modes[1]: unknown value 'fancy'; expected one of: partial, "
                        "single, consistent"));
  EXPECT_THAT(LoadError(tmp_, "name: t\nentries:\n  - {scenario: " + small +
                                  ", modes: [partial], seeds: [1, 2, 1]}\n"),
              HasSubstr("entries[0].seeds[0]: seed 1 is listed twice"));
  EXPECT_THAT(LoadError(tmp_, "name: t\nentries:\n  - {scenario: " + small +
                                  ", modes: [partial], seeds: []}\n"),
              HasSubstr("entries[0].seeds: needs at least one seed"));
  EXPECT_THAT(LoadError(tmp_, "name: t\nentries:\n  - {scenario: " + small +
                                  ", modes: [partial], seeds: [1], repeats: 0}\n"),
              HasSubstr("entries[0].repeats: integer 0 out of range [1, 1000]"));
  EXPECT_THAT(LoadError(tmp_, "name: t\nentries:\n  - {scenario: " + small +
                                  ", modes: [partial], seeds: [1]}\n  - {scenario: " + small +
                                  ", modes: [single], seeds: [2]}\n"),
              HasSubstr(":4: entries[1]: entry name 'small' is used twice; give one a name"));
}

TEST_F(SuiteSpecTest, BadTolerancesAreErrors) {
  EXPECT_THAT(LoadError(tmp_, Suite(tmp_, "  \"*.*.success_rate\": {abs: -1}\n")),
              HasSubstr("metrics.*.*.success_rate.abs: must be >= 0, got -1"));
  EXPECT_THAT(LoadError(tmp_, Suite(tmp_, "  \"*.*.success_rate\": {min: 1, max: 0.5}\n")),
              HasSubstr("max: must be >= min"));
  EXPECT_THAT(LoadError(tmp_, Suite(tmp_, "  \"*.*.success_rate\": {report: true, abs: 0.1}\n")),
              HasSubstr("report: true stands alone"));
  EXPECT_THAT(LoadError(tmp_, Suite(tmp_, "  \"*.*.success_rate\": {better: higher}\n")),
              HasSubstr("needs abs, rel, min or max (or report: true)"));
  EXPECT_THAT(LoadError(tmp_, Suite(tmp_, "  \"*.*.success_rate\": {better: up, abs: 0}\n")),
              HasSubstr("better: unknown value 'up'; expected one of: lower, higher"));
  EXPECT_THAT(LoadError(tmp_, Suite(tmp_, "  \"*.*.success_rate\": {tol: 0.1}\n")),
              HasSubstr("tol: unknown key"));
  EXPECT_THAT(LoadError(tmp_, Suite(tmp_, "  \"*.*.success_rate\": {abs: .nan}\n")),
              HasSubstr("must be a finite number"));
}

TEST_F(SuiteSpecTest, APatternThatMatchesNoMetricIsAnErrorWithTheNearestName) {
  const std::string error = LoadError(
      tmp_, Suite(tmp_, "  \"*.*.success_rate\": {abs: 0}\n  \"*.*.tracking_rms\": {abs: 0.02}\n"));
  EXPECT_THAT(error, HasSubstr("suite.yaml:8: metrics.*.*.tracking_rms: matches no metric"));
  EXPECT_THAT(error, HasSubstr("e.g. small.partial.success_rate"));
  EXPECT_THAT(error,
              HasSubstr("nearest metric name: 'tracking_error_m.pooled.rms'"));  // an abbreviation
  EXPECT_THAT(LoadError(tmp_, Suite(tmp_, "  \"*.*.tracking_error_m.poled.rms\": {abs: 0.02}\n")),
              HasSubstr("nearest metric name: 'tracking_error_m.pooled.rms'"));
  // Modes the suite does not run and entries it does not have match nothing either.
  EXPECT_THAT(LoadError(tmp_, Suite(tmp_, "  \"*.consistent.success_rate\": {abs: 0}\n")),
              HasSubstr("matches no metric"));
  EXPECT_THAT(LoadError(tmp_, Suite(tmp_, "  \"office.*.success_rate\": {abs: 0}\n")),
              HasSubstr("matches no metric"));
  EXPECT_THAT(LoadError(tmp_, Suite(tmp_, "  \"*.*.success rate\": {abs: 0}\n")),
              HasSubstr("unexpected character ' '"));
}

TEST_F(SuiteSpecTest, APatternOverriddenEverywhereByALaterOneIsAnError) {
  // General after specific: the specific rule never decides anything.
  EXPECT_THAT(
      LoadError(
          tmp_,
          Suite(tmp_,
                "  \"*.partial.success_rate\": {min: 1}\n  \"*.*.success_rate\": {abs: 0}\n")),
      HasSubstr("metrics.*.partial.success_rate: a later pattern overrides it for every metric it "
                "matches"));
  // Specific after general is the intended order.
  EXPECT_EQ(
      LoadError(
          tmp_,
          Suite(tmp_,
                "  \"*.*.success_rate\": {abs: 0}\n  \"*.partial.success_rate\": {min: 1}\n")),
      "");
}

}  // namespace
}  // namespace retrace::bench
