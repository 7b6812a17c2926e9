// The crowd check (bench/crowd/fundamental_diagram.hpp, `retrace crowd-check`): Weidmann's
// curve, the summary and bad input. Its crowd simulations are in
// fundamental_diagram_system_test.cpp.

#include "bench/crowd/fundamental_diagram.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bench/crowd/crowd_check.hpp"
#include "core/errors.hpp"

namespace retrace::bench {
namespace {

TEST(WeidmannCurve, MatchesKnownPoints) {
  // v0 (1 - exp(-1.913 (1/rho - 1/5.4))), evaluated by hand.
  EXPECT_NEAR(WeidmannSpeed(1.0), 1.34 * (1.0 - std::exp(-1.913 * (1.0 - 1.0 / 5.4))), 1e-12);
  EXPECT_NEAR(WeidmannSpeed(1.0), 1.058, 5e-4);
  EXPECT_NEAR(WeidmannSpeed(2.0), 0.606, 5e-4);
  EXPECT_NEAR(WeidmannSpeed(4.0), 0.1563, 5e-4);
  EXPECT_NEAR(WeidmannSpeed(0.1), 1.34, 1e-6);  // free walking
  EXPECT_DOUBLE_EQ(WeidmannSpeed(5.4), 0.0);    // jammed
  EXPECT_DOUBLE_EQ(WeidmannSpeed(6.0), 0.0);
  EXPECT_GT(WeidmannSpeed(1.5), WeidmannSpeed(1.6));
}

TEST(WeidmannCurve, RejectsNonPositiveDensity) {
  EXPECT_THROW(WeidmannSpeed(0.0), core::ConfigError);
  EXPECT_THROW(WeidmannSpeed(-1.0), core::ConfigError);
  EXPECT_THROW(WeidmannSpeed(std::numeric_limits<double>::quiet_NaN()), core::ConfigError);
}

TEST(CrowdCheck, RejectsBadDensities) {
  EXPECT_THROW(ParseDensityList("0.5,-1"), core::ConfigError);
  EXPECT_THROW(ParseDensityList("0"), core::ConfigError);
  EXPECT_THROW(ParseDensityList("1,abc"), core::ConfigError);
  EXPECT_THROW(ParseDensityList(""), core::ConfigError);
  EXPECT_THROW(ParseDensityList("6"), core::ConfigError);  // beyond Weidmann's jam density
  EXPECT_THROW(ValidateDensities({}), core::ConfigError);
  EXPECT_EQ(ParseDensityList("0.25, 1,2").size(), 3u);
  const FundamentalDiagramConfig config;
  EXPECT_THROW(RunFundamentalDiagram(config, CrowdFlow::kTwoWay, {1.0, -0.5}, 1),
               core::ConfigError);
  EXPECT_THROW(ParseFlowList("one_way,sideways"), core::ConfigError);
  EXPECT_THROW(ParseFlowList("two_way,two_way"), core::ConfigError);
  EXPECT_THROW(ParseFlowList(""), core::ConfigError);
  EXPECT_EQ(ParseFlowList("two_way, one_way"),
            (std::vector<CrowdFlow>{CrowdFlow::kTwoWay, CrowdFlow::kOneWay}));
}

TEST(CrowdCheck, RejectsUnknownAndInvalidKeys) {
  EXPECT_THROW(ReadFundamentalDiagramConfig({"no_such_key=1"}), core::ConfigError);
  EXPECT_THROW(ReadFundamentalDiagramConfig({"width=-1"}), core::ConfigError);
  const auto c =
      ReadFundamentalDiagramConfig({"width=3", "sim.crowd.social_force.relaxation_time=0.4"});
  EXPECT_DOUBLE_EQ(c.width, 3.0);
  EXPECT_DOUBLE_EQ(c.crowd.social_force.relaxation_time, 0.4);
}

TEST(CrowdCheck, SummaryPassesOnlyWithEveryDensityWithinTenPercent) {
  std::vector<FundamentalDiagramRow> rows(3);
  const double rho[3] = {0.25, 1.0, 2.0};
  const double v[3] = {1.30, 1.0, 0.9};
  for (int i = 0; i < 3; ++i) {
    rows[i].requested_density = rows[i].density = rho[i];
    rows[i].spawned = true;
    rows[i].mean_speed = v[i];
    rows[i].weidmann_speed = WeidmannSpeed(rho[i]);
    rows[i].relative_deviation = (v[i] - rows[i].weidmann_speed) / rows[i].weidmann_speed;
  }
  const FundamentalDiagramResult r = SummarizeDiagram(CrowdFlow::kTwoWay, rows);
  EXPECT_FALSE(r.pass);         // 0.9 m/s at 2 /m² is 49 % above 0.606
  EXPECT_EQ(r.rows_within, 2);  // 1.30 at 0.25 (-2.9 %), 1.0 at 1 (-5.5 %)
  EXPECT_NEAR(r.max_abs_deviation, 0.9 / WeidmannSpeed(2.0) - 1.0, 1e-12);
  EXPECT_GT(r.rms_deviation, 0.1);
  rows[2].mean_speed = 0.62;
  rows[2].relative_deviation = 0.62 / rows[2].weidmann_speed - 1.0;
  EXPECT_TRUE(SummarizeDiagram(CrowdFlow::kTwoWay, rows).pass);
  rows[2].spawned = false;  // a density that did not fit fails the check
  EXPECT_FALSE(SummarizeDiagram(CrowdFlow::kTwoWay, rows).pass);
}

}  // namespace
}  // namespace retrace::bench
