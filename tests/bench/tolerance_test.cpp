// The verdict on one suite metric against its baseline: deltas (absolute, relative), bounds,
// improvements, the direction of "worse", undefined (NaN) values and timing metrics.

#include "bench/suite/tolerance.hpp"
#include "tests/support/special_values.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace retrace::bench {
namespace {

using retrace::testing::kNaN;

Tolerance Abs(double abs) {
  Tolerance t;
  t.abs = abs;
  return t;
}

Tolerance Rel(double rel) {
  Tolerance t;
  t.rel = rel;
  return t;
}

Verdict V(std::string_view metric, std::optional<double> baseline, double now, const Tolerance& t) {
  return CheckMetric(metric, baseline, now, t).verdict;
}

TEST(Tolerance, AbsolutePassesWithinAndFailsBeyond) {
  const Tolerance t = Abs(0.02);
  EXPECT_EQ(V("tracking_error_m.pooled.rms", 0.10, 0.10, t), Verdict::kPass);
  EXPECT_EQ(V("tracking_error_m.pooled.rms", 0.10, 0.119, t), Verdict::kPass);
  EXPECT_EQ(V("tracking_error_m.pooled.rms", 0.10, 0.121, t), Verdict::kFail);
  const MetricCheck check = CheckMetric("tracking_error_m.pooled.rms", 0.10, 0.15, t);
  EXPECT_EQ(check.reason, "worse by 0.05 > 0.02");
}

TEST(Tolerance, ImprovedOnlyBeyondTheTolerance) {
  const Tolerance t = Abs(0.02);
  EXPECT_EQ(V("tracking_error_m.pooled.rms", 0.10, 0.085, t), Verdict::kPass);
  EXPECT_EQ(V("tracking_error_m.pooled.rms", 0.10, 0.07, t), Verdict::kImproved);
  // A zero tolerance calls any change one way or the other.
  EXPECT_EQ(V("collisions.pedestrian_incidents", 1.0, 0.0, Abs(0.0)), Verdict::kImproved);
  EXPECT_EQ(V("collisions.pedestrian_incidents", 1.0, 1.0, Abs(0.0)), Verdict::kPass);
  EXPECT_EQ(V("collisions.pedestrian_incidents", 1.0, 2.0, Abs(0.0)), Verdict::kFail);
}

TEST(Tolerance, RelativeScalesWithTheBaseline) {
  const Tolerance t = Rel(0.25);
  EXPECT_EQ(V("localization_error_m.pooled.rms", 0.2, 0.249, t), Verdict::kPass);
  EXPECT_EQ(V("localization_error_m.pooled.rms", 0.2, 0.251, t), Verdict::kFail);
  EXPECT_EQ(V("localization_error_m.pooled.rms", 2.0, 2.4, t), Verdict::kPass);
  EXPECT_EQ(V("localization_error_m.pooled.rms", 2.0, 1.4, t), Verdict::kImproved);
  // A zero baseline allows no increase at all.
  EXPECT_EQ(V("collisions.static_incidents", 0.0, 0.5, t), Verdict::kFail);
  EXPECT_EQ(V("collisions.static_incidents", 0.0, 0.0, t), Verdict::kPass);
}

TEST(Tolerance, AbsoluteAndRelativeTogetherAllowTheLooser) {
  Tolerance t = Abs(0.05);
  t.rel = 0.1;
  EXPECT_EQ(V("mean_time_s", 0.1, 0.14, t), Verdict::kPass);     // abs 0.05 > 10 % of 0.1
  EXPECT_EQ(V("mean_time_s", 100.0, 109.0, t), Verdict::kPass);  // 10 % of 100 > abs 0.05
  EXPECT_EQ(V("mean_time_s", 100.0, 111.0, t), Verdict::kFail);
}

TEST(Tolerance, MinBoundFailsBelowWhateverTheBaseline) {
  Tolerance t;
  t.min = 1.0;
  EXPECT_EQ(V("success_rate", 1.0, 1.0, t), Verdict::kBound);
  EXPECT_EQ(V("success_rate", 0.5, 1.0, t), Verdict::kBound);  // a bound ignores the baseline
  const MetricCheck check = CheckMetric("success_rate", 0.5, 0.75, t);
  EXPECT_EQ(check.verdict, Verdict::kFail);
  EXPECT_EQ(check.reason, "below min 1");
}

TEST(Tolerance, MaxBoundFailsAbove) {
  Tolerance t;
  t.max = 0.3;
  EXPECT_EQ(V("tracking_error_m.pooled.max", 0.2, 0.3, t), Verdict::kBound);
  const MetricCheck check = CheckMetric("tracking_error_m.pooled.max", 0.2, 0.31, t);
  EXPECT_EQ(check.verdict, Verdict::kFail);
  EXPECT_EQ(check.reason, "above max 0.3");
}

TEST(Tolerance, DeltaAndBoundCombine) {
  Tolerance t = Abs(0.1);
  t.max = 0.5;
  EXPECT_EQ(V("localization_error_m.pooled.max", 0.45, 0.52, t),
            Verdict::kFail);  // within abs, above max
  EXPECT_EQ(V("localization_error_m.pooled.max", 0.2, 0.35, t),
            Verdict::kFail);  // within max, beyond abs
  EXPECT_EQ(V("localization_error_m.pooled.max", 0.4, 0.25, t), Verdict::kImproved);
  EXPECT_EQ(V("localization_error_m.pooled.max", 0.4, 0.45, t), Verdict::kPass);
}

TEST(Tolerance, DirectionHigherIsBetterForSuccessProgressPrecisionRecallAndSpeed) {
  EXPECT_EQ(DefaultBetter("success_rate"), Better::kHigher);
  EXPECT_EQ(DefaultBetter("successes"), Better::kHigher);
  EXPECT_EQ(DefaultBetter("outcomes.success"), Better::kHigher);
  EXPECT_EQ(DefaultBetter("mean_progress_m"), Better::kHigher);
  EXPECT_EQ(DefaultBetter("dynamic_points.precision"), Better::kHigher);
  EXPECT_EQ(DefaultBetter("dynamic_points.recall"), Better::kHigher);
  EXPECT_EQ(DefaultBetter("cpu.real_time_factor"), Better::kHigher);
  EXPECT_EQ(DefaultBetter("collisions.min_clearance_m"), Better::kHigher);
  EXPECT_EQ(DefaultBetter("outcomes.lost"), Better::kLower);
  EXPECT_EQ(DefaultBetter("tracking_error_m.pooled.rms"), Better::kLower);
  EXPECT_EQ(DefaultBetter("switch_error.max_m"), Better::kLower);

  const Tolerance t = Abs(0.1);
  EXPECT_EQ(V("success_rate", 1.0, 0.8, t), Verdict::kFail);
  EXPECT_EQ(V("success_rate", 0.5, 0.8, t), Verdict::kImproved);
  EXPECT_EQ(V("tracking_error_m.pooled.rms", 1.0, 0.8, t), Verdict::kImproved);
}

TEST(Tolerance, ARulesBetterOverridesTheDefaultDirection) {
  Tolerance t = Abs(0.1);
  EXPECT_EQ(EffectiveBetter("tracking_error_m.pooled.rms", t), Better::kLower);
  EXPECT_EQ(EffectiveBetter("success_rate", t), Better::kHigher);
  t.better = Better::kHigher;
  EXPECT_EQ(EffectiveBetter("tracking_error_m.pooled.rms", t), Better::kHigher);
  t.better = Better::kLower;
  EXPECT_EQ(EffectiveBetter("success_rate", t), Better::kLower);
}

TEST(Tolerance, BetterOverridesTheDirection) {
  Tolerance t = Abs(0.1);
  t.better = Better::kHigher;
  EXPECT_EQ(V("switch_error.count", 3.0, 2.0, t),
            Verdict::kFail);  // fewer switches: the runs ended early
  EXPECT_EQ(V("switch_error.count", 3.0, 4.0, t), Verdict::kImproved);
  t.better = Better::kLower;
  EXPECT_EQ(V("success_rate", 1.0, 0.5, t), Verdict::kImproved);
}

TEST(Tolerance, UndefinedInBothPassesAndUndefinedOnOneSideFails) {
  const Tolerance t = Abs(0.1);
  EXPECT_EQ(V("switch_error.max_m", kNaN, kNaN, t), Verdict::kPass);
  const MetricCheck became = CheckMetric("switch_error.max_m", 0.1, kNaN, t);
  EXPECT_EQ(became.verdict, Verdict::kFail);
  EXPECT_EQ(became.reason, "became undefined");
  const MetricCheck appeared = CheckMetric("switch_error.max_m", kNaN, 0.1, t);
  EXPECT_EQ(appeared.verdict, Verdict::kFail);
  EXPECT_EQ(appeared.reason, "appeared (undefined in the baseline)");
  Tolerance bound;
  bound.min = 0.5;
  EXPECT_EQ(V("dynamic_points.recall", kNaN, kNaN, bound), Verdict::kPass);
  EXPECT_EQ(V("dynamic_points.recall", 0.8, kNaN, bound), Verdict::kFail);
}

TEST(Tolerance, MetricMissingFromTheBaselineFails) {
  const MetricCheck check = CheckMetric("tracking_error_m.pooled.rms", std::nullopt, 0.1, Abs(1.0));
  EXPECT_EQ(check.verdict, Verdict::kFail);
  EXPECT_EQ(check.reason, "not in the baseline");
}

TEST(Tolerance, TimingAndReportedMetricsAreNeverGated) {
  EXPECT_EQ(V("cpu.real_time_factor", 100.0, 1.0, Abs(0.0)), Verdict::kReport);
  EXPECT_EQ(V("cpu.localizer_update_mean_ms", 1.0, kNaN, Abs(0.0)), Verdict::kReport);
  Tolerance report;
  report.report = true;
  EXPECT_EQ(V("success_rate", 1.0, 0.0, report), Verdict::kReport);
  EXPECT_EQ(V("success_rate", std::nullopt, 0.0, report), Verdict::kReport);
  EXPECT_FALSE(IsFailure(Verdict::kReport));
  EXPECT_TRUE(IsFailure(Verdict::kFail));
}

TEST(Tolerance, DescribeTolerance) {
  Tolerance t = Abs(0.02);
  t.rel = 0.25;
  t.min = 0.0;
  t.max = 0.3;
  t.better = Better::kHigher;
  EXPECT_EQ(DescribeTolerance(t), "abs 0.02, rel 25 %, min 0, max 0.3, higher better");
  Tolerance report;
  report.report = true;
  EXPECT_EQ(DescribeTolerance(report), "report");
}

}  // namespace
}  // namespace retrace::bench
