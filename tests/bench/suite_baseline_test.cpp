// Baselines: what they record, that they read back exactly (NaN included), that a baseline
// of another suite or of other entry definitions is refused, and the comparison report built
// from a baseline and results (no simulation here: the results are made up).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bench/suite/baseline.hpp"
#include "bench/suite/suite_report.hpp"
#include "bench/suite/suite_spec.hpp"
#include "core/errors.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/special_values.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
namespace {

using ::testing::HasSubstr;
using SuiteBaselineTest = retrace::testing::TempDirTest;

using retrace::testing::kSource;
using retrace::testing::kNaN;

SuiteSpec Spec(const retrace::testing::TempDir& tmp, const std::string& seeds = "[1, 2]") {
  const std::string small =
      std::filesystem::relative(kSource / "scenarios/small.yaml", tmp.path()).string();
  return LoadSuiteSpec(tmp.Write("suite.yaml",
                                 "name: t\n"
                                 "entries:\n"
                                 "  - {scenario: " +
                                     small + ", modes: [partial, single], seeds: " + seeds +
                                     ", set: {nav.localizer.particles: 300}}\n"
                                     "metrics:\n"
                                     "  \"*.*.success_rate\": {abs: 0}\n"
                                     "  \"*.partial.success_rate\": {min: 1}\n"
                                     "  \"*.*.tracking_error_m.pooled.rms\": {abs: 0.02}\n"
                                     "  \"*.*.switch_error.max_m\": {rel: 0.5}\n"
                                     "  \"*.*.cpu.real_time_factor\": {report: true}\n"));
}

// Results where every metric of every mode is 0.1 on each seed, then the given values.
SuiteResults Results(const SuiteSpec& spec, const std::map<std::string, double>& values) {
  SuiteResults results;
  for (const std::string& name : SuiteMetricNames(spec)) results.metrics[name] = {0.1, {0.1, 0.1}};
  for (const auto& [name, value] : values) results.metrics[name] = {value, {value, value}};
  results.teaching_drives = 2;
  results.playback_runs = 8;
  return results;
}

const ReportRow& Row(const SuiteReport& report, const std::string& name) {
  for (const ReportRow& row : report.rows) {
    if (row.name == name) return row;
  }
  throw std::runtime_error("no row " + name);
}

TEST_F(SuiteBaselineTest, RecordsEverythingAndReadsBackExactly) {
  const SuiteSpec spec = Spec(tmp_);
  const SuiteResults results =
      Results(spec, {{"small.partial.switch_error.max_m", kNaN},
                     {"small.partial.cpu.real_time_factor", 84.25},
                     {"small.single.tracking_error_m.pooled.rms", 0.1 + 1e-17}});
  const Baseline made = MakeBaseline(spec, results);
  EXPECT_EQ(made.suite, "t");
  EXPECT_EQ(made.suite_digest, spec.digest);
  EXPECT_FALSE(made.git_revision.empty());
  EXPECT_EQ(made.date.size(), 20u);  // 2025-06-01T12:00:00Z
  // Timing metrics go apart from the navigation metrics.
  EXPECT_EQ(made.timing.count("small.partial.cpu.real_time_factor"), 1u);
  EXPECT_EQ(made.metrics.count("small.partial.cpu.real_time_factor"), 0u);
  EXPECT_EQ(made.metrics.size() + made.timing.size(), results.metrics.size());

  const std::filesystem::path file = tmp_.path() / "baselines" / "t.json";
  WriteBaseline(file, made);
  const Baseline read = ReadBaseline(file);
  EXPECT_EQ(read.suite, made.suite);
  EXPECT_EQ(read.suite_file, made.suite_file);
  EXPECT_EQ(read.git_revision, made.git_revision);
  EXPECT_EQ(read.date, made.date);
  EXPECT_EQ(read.entries, made.entries);
  ASSERT_EQ(read.metrics.size(), made.metrics.size());
  for (const auto& [name, value] : made.metrics) {
    if (std::isnan(value)) {
      EXPECT_TRUE(std::isnan(read.metrics.at(name))) << name;
    } else {
      EXPECT_EQ(read.metrics.at(name), value) << name;  // bit for bit
    }
  }
  EXPECT_EQ(read.Find("small.partial.cpu.real_time_factor"), 84.25);
  EXPECT_FALSE(read.Find("small.partial.nothing").has_value());
  EXPECT_NO_THROW(CheckBaselineMatches(read, spec, file));
  EXPECT_THAT(tmp_.Read(file), HasSubstr("\"format\": \"retrace-baseline/1\""));
}

TEST_F(SuiteBaselineTest, BrokenBaselinesAreIoErrorsNamingTheFile) {
  auto error = [&](const std::string& text) {
    try {
      ReadBaseline(tmp_.Write("b.json", text));
    } catch (const core::IoError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_THAT(error("{\"format\": "), HasSubstr("b.json: invalid JSON"));
  EXPECT_THAT(error("[]"), HasSubstr("b.json: not a retrace baseline: expected a JSON object"));
  EXPECT_THAT(error("{\"format\": \"something else\"}"),
              HasSubstr("'format' must be \"retrace-baseline/1\""));
  const std::string header =
      "{\"format\": \"retrace-baseline/1\", \"suite\": \"t\", \"suite_file\": \"s\", "
      "\"suite_digest\": \"d\", "
      "\"git_revision\": \"r\", \"build_type\": \"Release\", \"date\": \"x\", \"entries\": [], ";
  EXPECT_THAT(error(header + "\"metrics\": {\"a\": \"high\"}, \"timing\": {}}"),
              HasSubstr("metrics.a must be a number or null"));
  EXPECT_THAT(error(header + "\"timing\": {}}"), HasSubstr("'metrics' must be an object"));
  EXPECT_EQ(error(header + "\"metrics\": {\"a\": null}, \"timing\": {}}"), "");
  try {
    ReadBaseline(tmp_.path() / "missing.json");
    FAIL() << "no error";
  } catch (const core::IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing.json: cannot open file"));
  }
}

TEST_F(SuiteBaselineTest, ABaselineOfAnotherSuiteOrOtherEntriesIsRefused) {
  const SuiteSpec spec = Spec(tmp_);
  Baseline baseline = MakeBaseline(spec, Results(spec, {}));
  const std::filesystem::path file = "b.json";
  auto error = [&](const Baseline& b) {
    try {
      CheckBaselineMatches(b, spec, file);
    } catch (const core::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error(baseline), "");

  Baseline other = baseline;
  other.suite = "full";
  EXPECT_THAT(error(other), HasSubstr("b.json is the baseline of suite 'full', not of 't'"));

  const Baseline other_seeds = MakeBaseline(Spec(tmp_, "[1, 3]"), Results(spec, {}));
  EXPECT_THAT(
      error(other_seeds),
      HasSubstr("b.json: entry 'small' has changed since the baseline (seeds [1,3] -> [1,2])"));
  EXPECT_THAT(error(other_seeds), HasSubstr("--update-baseline"));

  Baseline renamed = baseline;
  renamed.entries[0]["name"] = "tiny";
  EXPECT_THAT(error(renamed), HasSubstr("entry 'small' is not in the baseline"));

  Baseline extra = baseline;
  extra.entries.push_back(extra.entries[0]);
  extra.entries[1]["name"] = "office";
  EXPECT_THAT(error(extra), HasSubstr("entry 'office' of the baseline is no longer in the suite"));
}

TEST_F(SuiteBaselineTest, ReportGatesOnlyDecidedMetricsAndCountsRegressions) {
  const SuiteSpec spec = Spec(tmp_);
  Baseline baseline =
      MakeBaseline(spec, Results(spec, {{"small.partial.success_rate", 1.0},
                                        {"small.single.success_rate", 0.5},
                                        {"small.single.switch_error.max_m", kNaN}}));
  const SuiteResults now =
      Results(spec, {{"small.partial.success_rate", 0.5},                  // below min 1
                     {"small.single.success_rate", 1.0},                   // improved
                     {"small.partial.tracking_error_m.pooled.rms", 0.11},  // within 0.02
                     {"small.single.tracking_error_m.pooled.rms", 0.2},    // worse by 0.1
                     {"small.single.switch_error.max_m", 0.3},             // appeared
                     {"small.partial.cpu.real_time_factor", 1.0}});
  const SuiteReport report = CompareWithBaseline(spec, now, &baseline);
  EXPECT_TRUE(report.compared);
  // 5 rules' metrics in 2 modes: success rate, tracking, switch error, rtf.
  ASSERT_EQ(report.rows.size(), 8u);
  EXPECT_EQ(report.failures, 3);
  EXPECT_EQ(report.improved, 1);
  EXPECT_EQ(report.reported, 2);
  EXPECT_EQ(report.checked, 6);
  EXPECT_EQ(Row(report, "small.partial.success_rate").check.reason, "below min 1");
  EXPECT_EQ(Row(report, "small.partial.success_rate").pattern, "*.partial.success_rate");
  EXPECT_EQ(Row(report, "small.single.success_rate").check.verdict, Verdict::kImproved);
  EXPECT_EQ(Row(report, "small.partial.tracking_error_m.pooled.rms").check.verdict, Verdict::kPass);
  EXPECT_EQ(Row(report, "small.single.tracking_error_m.pooled.rms").check.verdict, Verdict::kFail);
  EXPECT_EQ(Row(report, "small.single.switch_error.max_m").check.reason,
            "appeared (undefined in the baseline)");
  EXPECT_EQ(Row(report, "small.partial.cpu.real_time_factor").check.verdict, Verdict::kReport);
  // Rows by mode, then by rule: partial's first, success rate before tracking.
  EXPECT_EQ(report.rows[0].name, "small.partial.success_rate");
  EXPECT_EQ(report.rows[1].name, "small.partial.tracking_error_m.pooled.rms");
  EXPECT_EQ(report.rows[4].name, "small.single.success_rate");

  const std::string table = ReportTable(report);
  EXPECT_THAT(table, HasSubstr("small.single.tracking_error_m.pooled.rms"));
  EXPECT_THAT(table, HasSubstr("FAIL      abs 0.02; worse by 0.1 > 0.02"));
  ReportContext context;
  context.baseline = &baseline;
  context.baseline_file = "b.json";
  EXPECT_THAT(ReportMarkdown(report, context), HasSubstr("# Suite t: FAIL (3 regressions)"));
  const nlohmann::json json = ReportJson(report, context, spec, now);
  EXPECT_EQ(json["verdict"], "FAIL");
  EXPECT_EQ(json["counts"]["failures"], 3);
  EXPECT_EQ(json["metrics"]["small.single.switch_error.max_m"]["per_seed"].size(), 2u);
}

TEST_F(SuiteBaselineTest, AMetricTheBaselineHasButNoLongerComputedFails) {
  const SuiteSpec spec = Spec(tmp_);
  const std::map<std::string, double> all_succeed = {{"small.partial.success_rate", 1.0}};
  Baseline baseline = MakeBaseline(spec, Results(spec, all_succeed));
  SuiteResults now = Results(spec, all_succeed);
  now.metrics.erase("small.single.tracking_error_m.pooled.rms");
  const SuiteReport report = CompareWithBaseline(spec, now, &baseline);
  EXPECT_EQ(Row(report, "small.single.tracking_error_m.pooled.rms").check.reason,
            "no longer computed");
  EXPECT_EQ(report.failures, 1);
  // Without a baseline nothing fails: the values are only listed (recording the first one).
  const SuiteReport first = CompareWithBaseline(spec, Results(spec, {}), nullptr);
  EXPECT_FALSE(first.compared);
  EXPECT_EQ(first.failures, 0);
  EXPECT_THAT(ReportTable(first), HasSubstr(" new "));
}

TEST(SuiteReport, SeedSpreadIsTheSampleStandardDeviationOfTheDefinedValues) {
  EXPECT_DOUBLE_EQ(SeedStdDev({1.0, 3.0}), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(SeedStdDev({1.0, kNaN, 3.0}), std::sqrt(2.0));
  EXPECT_TRUE(std::isnan(SeedStdDev({1.0, kNaN})));
  EXPECT_DOUBLE_EQ(MeanOfDefined({1.0, kNaN, 3.0}), 2.0);
  EXPECT_TRUE(std::isnan(MeanOfDefined({kNaN, kNaN})));
}

}  // namespace
}  // namespace retrace::bench
