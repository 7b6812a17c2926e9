// The JUnit XML of `retrace bench --junit` on made-up reports (no simulation): a testsuite per
// entry and mode, a testcase per gated metric, a failure with baseline, now, delta and tolerance
// exactly where `retrace bench` exits 1, the run's provenance as properties, and text escaped so
// that any XML parser reads it. tests/cli/bench_ci_files_test.sh reads real files with junitparser.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "bench/suite/baseline.hpp"
#include "bench/suite/junit_report.hpp"
#include "bench/suite/suite_report.hpp"
#include "bench/suite/suite_spec.hpp"
#include "bench/suite/tolerance.hpp"

namespace retrace::bench {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace suite_junit_test {

using ::testing::HasSubstr;
using ::testing::Not;

Tolerance Abs(double abs) {
  Tolerance t;
  t.abs = abs;
  return t;
}

Tolerance Report() {
  Tolerance t;
  t.report = true;
  return t;
}

// A row judged as CompareWithBaseline judges it.
ReportRow Row(const std::string& name, std::optional<double> baseline, double now,
              const Tolerance& tolerance) {
  ReportRow row;
  row.name = name;
  row.baseline = baseline;
  row.now = now;
  row.seed_sd = 0.05;
  row.pattern = "*.*." + SplitSuiteMetricName(name).metric;
  row.tolerance = tolerance;
  row.check = CheckMetric(SplitSuiteMetricName(name).metric, baseline, now, tolerance);
  return row;
}

// Two entries, three modes; the test room's partial maps have only a reported metric.
SuiteReport MadeUpReport(double office_success_now) {
  SuiteReport report;
  report.suite = "ci";
  report.compared = true;
  report.rows = {
      Row("office.partial.success_rate", 0.9375, office_success_now, Abs(0.25)),
      Row("office.partial.tracking_error_m.pooled.rms", 0.08, 0.081, Abs(0.032)),
      Row("office.partial.localization_error_m.pooled.rms", 0.2, 0.9, Report()),
      Row("office.consistent.tracking_error_m.pooled.rms", 0.037, 0.036, Abs(0.024)),
      Row("small.partial.cpu.real_time_factor", 80.0, 60.0, Report()),
  };
  for (const ReportRow& row : report.rows) {
    if (IsFailure(row.check.verdict)) ++report.failures;
  }
  return report;
}

ReportContext Context() {
  ReportContext context;
  context.suite_file = "bench/suites/ci.yaml";
  context.suite_digest = "fnv1a64:0123456789abcdef";
  context.git_revision = "abc123def456";
  context.version = "0.1.0";
  context.date = "2026-01-02T03:04:05Z";
  context.wall_time_s = 181.25;
  context.jobs = 2;
  return context;
}

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(SuiteJunit, OneTestsuitePerEntryAndModeOneTestcasePerGatedMetric) {
  const std::string xml = JunitXml(MadeUpReport(0.9375), Context());
  EXPECT_EQ(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"ci\"", 0),
            0u);
  EXPECT_EQ(Count(xml, "<testsuite "), 2);  // small.partial gates nothing: no testsuite
  EXPECT_THAT(xml, HasSubstr("<testsuite name=\"office.partial\" tests=\"2\" failures=\"0\""));
  EXPECT_THAT(xml, HasSubstr("<testsuite name=\"office.consistent\" tests=\"1\" failures=\"0\""));
  EXPECT_THAT(xml, HasSubstr("<testcase classname=\"office.partial\" "
                             "name=\"office.partial.success_rate\" time=\"0\"/>"));
  EXPECT_THAT(xml, HasSubstr("name=\"office.consistent.tracking_error_m.pooled.rms\""));
  EXPECT_EQ(Count(xml, "<testcase "), 3);
  // Reported metrics are left out, however much they moved.
  EXPECT_THAT(xml, Not(HasSubstr("localization_error_m.pooled.rms")));
  EXPECT_THAT(xml, Not(HasSubstr("real_time_factor")));
  EXPECT_THAT(xml, HasSubstr("<testsuites name=\"ci\" tests=\"3\" failures=\"0\" errors=\"0\" "
                             "skipped=\"0\" time=\"181.250\">"));
  EXPECT_THAT(xml, Not(HasSubstr("<failure")));
  EXPECT_EQ(xml.substr(xml.size() - 14), "</testsuites>\n");
}

TEST(SuiteJunit, ARegressionIsAFailureWithBaselineNowDeltaAndTolerance) {
  const SuiteReport report = MadeUpReport(0.1875);
  ASSERT_EQ(report.failures, 1);
  const std::string xml = JunitXml(report, Context());
  EXPECT_EQ(Count(xml, "<failure "), 1);
  EXPECT_THAT(xml, HasSubstr("<testsuites name=\"ci\" tests=\"3\" failures=\"1\""));
  EXPECT_THAT(xml, HasSubstr("<testsuite name=\"office.partial\" tests=\"2\" failures=\"1\""));
  EXPECT_THAT(xml, HasSubstr("<testsuite name=\"office.consistent\" tests=\"1\" failures=\"0\""));
  EXPECT_THAT(xml, HasSubstr("<testcase classname=\"office.partial\" "
                             "name=\"office.partial.success_rate\" time=\"0\">\n"
                             "      <failure type=\"regression\" message=\"baseline 0.9375, now "
                             "0.1875, delta -0.75, tolerance abs 0.25: worse by 0.75 &gt; "
                             "0.25\">office.partial.success_rate regressed: worse by 0.75 &gt; "
                             "0.25\nbaseline: 0.9375\nnow: 0.1875 (mean over the seeds; seed sd "
                             "0.05)\ndelta: -0.75\ntolerance: abs 0.25 (rule "
                             "&quot;*.*.success_rate&quot;)\n</failure>\n    </testcase>\n"));
  // The passing metric of the same testsuite stays a plain testcase.
  EXPECT_THAT(xml, HasSubstr("name=\"office.partial.tracking_error_m.pooled.rms\" time=\"0\"/>"));
}

TEST(SuiteJunit, TheFailureSaysWhichBaselineItWasComparedWith) {
  Baseline baseline;
  baseline.git_revision = "0ld0ld0ld0ld";
  baseline.date = "2025-12-01T00:00:00Z";
  ReportContext context = Context();
  context.baseline = &baseline;
  context.baseline_file = "results/baselines/ci.json";
  const std::string xml = JunitXml(MadeUpReport(0.1875), context);
  EXPECT_THAT(xml, HasSubstr("baseline: 0.9375 (results/baselines/ci.json, git 0ld0ld0ld0ld, "
                             "2025-12-01T00:00:00Z)\n"));
  EXPECT_THAT(xml,
              HasSubstr("<property name=\"baseline_file\" value=\"results/baselines/ci.json\"/>"));
  EXPECT_THAT(xml, HasSubstr("<property name=\"baseline_git_revision\" value=\"0ld0ld0ld0ld\"/>"));
}

TEST(SuiteJunit, WithoutABaselineOrWhenRecordingOneNothingFails) {
  // The first recording: every gated metric is "not in the baseline", yet bench exits 0.
  SuiteReport first = MadeUpReport(0.1875);
  first.compared = false;
  for (ReportRow& row : first.rows) {
    row.baseline.reset();
    row.check =
        CheckMetric(SplitSuiteMetricName(row.name).metric, std::nullopt, *row.now, row.tolerance);
  }
  const std::string xml = JunitXml(first, Context());
  EXPECT_EQ(Count(xml, "<testcase "), 3);
  EXPECT_THAT(xml, Not(HasSubstr("<failure")));
  EXPECT_THAT(xml, HasSubstr("failures=\"0\""));

  // --update-baseline against an old baseline: compared for information, judged by no one.
  ReportContext recording = Context();
  recording.recording = true;
  const std::string recorded = JunitXml(MadeUpReport(0.1875), recording);
  EXPECT_THAT(recorded, Not(HasSubstr("<failure")));
  EXPECT_THAT(recorded, HasSubstr("<property name=\"recording\""));
}

TEST(SuiteJunit, AReportedMetricNoLongerComputedFailsAsTheExitCodeDoes) {
  SuiteReport report = MadeUpReport(0.9375);
  ReportRow& gone = report.rows[2];  // office.partial.localization_error_m.pooled.rms, report
  gone.now.reset();
  gone.check = {Verdict::kFail, "no longer computed"};
  const std::string xml = JunitXml(report, Context());
  EXPECT_EQ(Count(xml, "<testcase "), 4);
  EXPECT_THAT(xml, HasSubstr("message=\"baseline 0.2, now -, delta -, tolerance report: no "
                             "longer computed\""));
}

TEST(SuiteJunit, PropertiesHoldTheVersionRevisionWallTimeAndCommandLine) {
  ReportContext context = Context();
  context.overrides = {"nav.localizer.rejection.enabled=false"};
  context.only = {"office.partial"};
  const std::string xml = JunitXml(MadeUpReport(0.9375), context);
  // The same properties in every testsuite.
  EXPECT_EQ(Count(xml, "<property name=\"retrace_version\" value=\"0.1.0\"/>"), 2);
  EXPECT_EQ(Count(xml, "<property name=\"git_revision\" value=\"abc123def456\"/>"), 2);
  EXPECT_EQ(Count(xml, "<property name=\"wall_time_s\" value=\"181.250\"/>"), 2);
  EXPECT_THAT(xml, HasSubstr("<property name=\"date\" value=\"2026-01-02T03:04:05Z\"/>"));
  EXPECT_THAT(xml, HasSubstr("timestamp=\"2026-01-02T03:04:05Z\""));
  EXPECT_THAT(xml, HasSubstr("<property name=\"jobs\" value=\"2\"/>"));
  EXPECT_THAT(xml, HasSubstr("<property name=\"suite_file\" value=\"bench/suites/ci.yaml\"/>"));
  EXPECT_THAT(
      xml, HasSubstr("<property name=\"set\" value=\"nav.localizer.rejection.enabled=false\"/>"));
  EXPECT_THAT(xml, HasSubstr("<property name=\"only\" value=\"office.partial\"/>"));
  // No revision known: no property rather than an empty one.
  context.git_revision.clear();
  EXPECT_THAT(JunitXml(MadeUpReport(0.9375), context), Not(HasSubstr("\"git_revision\"")));
}

TEST(SuiteJunit, EscapesMarkupControlCharactersAndInvalidUtf8) {
  ReportContext context = Context();
  context.overrides = {"name=a<b&c\"d'e>", "bad\xFF\xC3(utf8", "tab\tline\nbell\x07",
                       "caf\xC3\xA9 \xEF\xBF\xBF"};
  const std::string xml = JunitXml(MadeUpReport(0.1875), context);
  EXPECT_THAT(xml, HasSubstr("value=\"name=a&lt;b&amp;c&quot;d&#39;e&gt;\""));
  // Stray and cut sequences become U+FFFD; so do characters XML 1.0 cannot hold.
  EXPECT_THAT(xml, HasSubstr("value=\"bad\xEF\xBF\xBD\xEF\xBF\xBD(utf8\""));
  EXPECT_THAT(xml, HasSubstr("value=\"tab&#9;line&#10;bell\xEF\xBF\xBD\""));
  EXPECT_THAT(xml, HasSubstr("value=\"caf\xC3\xA9 \xEF\xBF\xBD\""));  // valid UTF-8 kept
  EXPECT_THAT(xml, Not(HasSubstr("\xFF")));
  EXPECT_THAT(xml, Not(HasSubstr("\x07")));
}

}  // namespace suite_junit_test
}  // namespace retrace::bench
