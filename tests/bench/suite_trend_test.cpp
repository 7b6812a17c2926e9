// The trend file of `retrace bench --trend` on made-up reports (no simulation): every reported or
// gated metric in the Bencher Metric Format, its measure the direction that is better (from the
// rule that decides it), value the mean, lower and upper values the seeds' extremes.
// tests/cli/bench_ci_files_test.sh checks real files against the format's published schema.

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "bench/suite/suite_report.hpp"
#include "bench/suite/suite_runner.hpp"
#include "bench/suite/trend_file.hpp"
#include "tests/support/special_values.hpp"

namespace retrace::bench {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace suite_trend_test {

using retrace::testing::kNaN;

ReportRow Row(const std::string& name, std::optional<double> now, Tolerance tolerance = {}) {
  ReportRow row;
  row.name = name;
  row.now = now;
  if (!tolerance.has_delta() && !tolerance.has_bound() && !tolerance.report) tolerance.abs = 0.1;
  row.tolerance = tolerance;
  return row;
}

TEST(SuiteTrend, TheMeasureIsTheDirectionThatIsBetter) {
  EXPECT_EQ(TrendMeasure(Better::kLower), "lower-is-better");
  EXPECT_EQ(TrendMeasure(Better::kHigher), "higher-is-better");

  Tolerance reported;
  reported.report = true;
  Tolerance fewer_is_worse;
  fewer_is_worse.abs = 1.0;
  fewer_is_worse.better = Better::kHigher;
  SuiteReport report;
  report.rows = {Row("office.partial.success_rate", 0.9375),
                 Row("office.partial.tracking_error_m.pooled.rms", 0.08),
                 Row("office.partial.localization_error_m.pooled.rms", 0.2, reported),
                 Row("office.partial.cpu.real_time_factor", 21.0, reported),
                 Row("office.partial.switch_error.count", 3.0, fewer_is_worse)};
  const nlohmann::ordered_json trend = TrendJson(report, SuiteResults{});
  ASSERT_EQ(trend.size(), 5u);
  EXPECT_EQ(trend["office.partial.success_rate"],
            nlohmann::ordered_json({{"higher-is-better", {{"value", 0.9375}}}}));
  EXPECT_EQ(trend["office.partial.tracking_error_m.pooled.rms"],
            nlohmann::ordered_json({{"lower-is-better", {{"value", 0.08}}}}));
  // Reported metrics are there too, in the direction of their name.
  EXPECT_TRUE(trend["office.partial.localization_error_m.pooled.rms"].contains("lower-is-better"));
  EXPECT_TRUE(trend["office.partial.cpu.real_time_factor"].contains("higher-is-better"));
  // A rule's `better` decides over the name.
  EXPECT_TRUE(trend["office.partial.switch_error.count"].contains("higher-is-better"));
}

TEST(SuiteTrend, ValueIsTheMeanAndTheBoundsTheSeedsExtremes) {
  SuiteReport report;
  report.rows = {Row("small.partial.repeatability_m", 0.02)};
  SuiteResults results;
  results.metrics["small.partial.repeatability_m"] = {0.02, {0.03, kNaN, 0.01, 0.02}};
  const nlohmann::ordered_json measure =
      TrendJson(report, results)["small.partial.repeatability_m"]["lower-is-better"];
  EXPECT_EQ(measure["value"], 0.02);
  EXPECT_EQ(measure["lower_value"], 0.01);
  EXPECT_EQ(measure["upper_value"], 0.03);
  EXPECT_EQ(measure.begin().key(), "value");

  // No seed defined: no bounds.
  results.metrics["small.partial.repeatability_m"].per_seed = {kNaN, kNaN};
  EXPECT_FALSE(
      TrendJson(report, results)["small.partial.repeatability_m"]["lower-is-better"].contains(
          "lower_value"));
}

TEST(SuiteTrend, UndefinedMetricsAreLeftOutAndTheReportsOrderKept) {
  SuiteReport report;
  report.rows = {Row("small.partial.tracking_error_m.pooled.rms", 0.1),
                 Row("small.partial.switch_error.max_m", kNaN),
                 Row("small.partial.dynamic_points.recall", std::nullopt),
                 Row("office.partial.success_rate", 1.0),
                 Row("small.consistent.success_rate", 1.0)};
  const nlohmann::ordered_json trend = TrendJson(report, SuiteResults{});
  std::vector<std::string> keys;
  for (const auto& [key, value] : trend.items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"small.partial.tracking_error_m.pooled.rms",
                                            "office.partial.success_rate",
                                            "small.consistent.success_rate"}));
  EXPECT_EQ(TrendJson(SuiteReport{}, SuiteResults{}), nlohmann::ordered_json::object());
}

}  // namespace suite_trend_test
}  // namespace retrace::bench
