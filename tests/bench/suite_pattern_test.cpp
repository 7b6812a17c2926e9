// Suite metric names and the patterns that select them: `*` inside one dotted part, `**`
// across parts, the last matching pattern decides.

#include <gtest/gtest.h>

#include "bench/suite/metric_pattern.hpp"

namespace retrace::bench {
namespace {

TEST(SuitePattern, StarMatchesWithinOneDottedPart) {
  EXPECT_TRUE(MatchMetricPattern("*.*.tracking_error_m.pooled.rms",
                                 "office.partial.tracking_error_m.pooled.rms"));
  EXPECT_TRUE(MatchMetricPattern("*.partial.success_rate", "small.partial.success_rate"));
  EXPECT_FALSE(MatchMetricPattern("*.partial.success_rate", "small.single.success_rate"));
  // One star never spans a dot: "*.success_rate" is not "<anything>.success_rate".
  EXPECT_FALSE(MatchMetricPattern("*.success_rate", "small.partial.success_rate"));
  EXPECT_FALSE(
      MatchMetricPattern("*.*.tracking_error_m.*", "small.partial.tracking_error_m.pooled.rms"));
}

TEST(SuitePattern, StarMatchesARunOfCharactersInsideAPart) {
  EXPECT_TRUE(MatchMetricPattern("*.*.localization_error_*.pooled.rms",
                                 "small.partial.localization_error_m.pooled.rms"));
  EXPECT_TRUE(MatchMetricPattern("*.*.localization_error_*.pooled.rms",
                                 "small.partial.localization_error_rad.pooled.rms"));
  EXPECT_TRUE(MatchMetricPattern("*.*.tracking_error_m.pooled.*",
                                 "small.single.tracking_error_m.pooled.p95"));
  EXPECT_TRUE(MatchMetricPattern("off*.*.success_rate", "office.single.success_rate"));
  EXPECT_TRUE(
      MatchMetricPattern("*.*.success_rate*", "small.single.success_rate"));     // an empty run
  EXPECT_FALSE(MatchMetricPattern("*.*.success", "small.single.success_rate"));  // whole names only
}

TEST(SuitePattern, DoubleStarMatchesAcrossDots) {
  EXPECT_TRUE(MatchMetricPattern("small.**", "small.partial.collisions.min_clearance_m"));
  EXPECT_TRUE(MatchMetricPattern("**.cpu.*", "campus.single.cpu.real_time_factor"));
  EXPECT_TRUE(MatchMetricPattern("**", "a.b.c"));
  EXPECT_FALSE(MatchMetricPattern("small.**", "office.partial.success_rate"));
  EXPECT_FALSE(MatchMetricPattern("**.rms", "small.partial.tracking_error_m.pooled.max"));
}

TEST(SuitePattern, ExactNamesMatchOnlyThemselves) {
  EXPECT_TRUE(MatchMetricPattern("small.partial.success_rate", "small.partial.success_rate"));
  EXPECT_FALSE(MatchMetricPattern("small.partial.success_rate", "small.partial.success_rates"));
  EXPECT_FALSE(MatchMetricPattern("small.partial.success_rate", "small.partial.success_rat"));
}

TEST(SuitePattern, MalformedPatternsAreNamed) {
  EXPECT_EQ(PatternProblem("*.*.success_rate"), "");
  EXPECT_EQ(PatternProblem("small.**"), "");
  EXPECT_EQ(PatternProblem(""), "empty pattern");
  EXPECT_EQ(PatternProblem("*..success_rate"), "empty dotted part");
  EXPECT_EQ(PatternProblem(".success_rate"), "empty dotted part");
  EXPECT_EQ(PatternProblem("*.*.success rate"),
            "unexpected character ' ' (patterns use letters, digits, _ - . * **)");
  EXPECT_EQ(PatternProblem("*.*.success_rate?"),
            "unexpected character '?' (patterns use letters, digits, _ - . * **)");
  EXPECT_EQ(PatternProblem("***.x"), "'***' is not a wildcard; use * or **");
}

TEST(SuitePattern, TheLastMatchingPatternDecides) {
  const std::vector<std::string> patterns = {"*.*.success_rate", "*.partial.success_rate",
                                             "office.*.tracking_error_m.pooled.rms"};
  EXPECT_EQ(DecidingPattern(patterns, "small.single.success_rate"), 0);
  EXPECT_EQ(DecidingPattern(patterns, "small.partial.success_rate"), 1);
  EXPECT_EQ(DecidingPattern(patterns, "office.partial.tracking_error_m.pooled.rms"), 2);
  EXPECT_EQ(DecidingPattern(patterns, "small.partial.tracking_error_m.pooled.rms"), -1);
}

}  // namespace
}  // namespace retrace::bench
