// The crowd check (bench/crowd/fundamental_diagram.hpp, `retrace crowd-check`): Weidmann's
// curve, short runs of both flows and both crowd models, determinism per seed and bad input.

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

// A short, small ring keeps the test fast.
FundamentalDiagramConfig SmallRing() {
  FundamentalDiagramConfig c;
  c.inner_radius = 3.0;
  c.width = 3.0;
  c.warmup = 3.0;
  c.duration = 4.0;
  return c;
}

TEST(CrowdCheck, AlmostAloneEveryoneWalksNearTheDesiredSpeed) {
  const FundamentalDiagramConfig config = SmallRing();
  // 0.1 /m² in a 47 m² ring: 5 people. Desired speeds are N(1.34, 0.26): over a few seeds the
  // mean speed along the corridor stays within 10 % of 1.34 m/s.
  double sum = 0.0;
  for (std::uint64_t seed : {1, 2, 3, 4}) {
    const FundamentalDiagramRow row = RunDensity(config, CrowdFlow::kTwoWay, 0.1, seed, 0);
    ASSERT_TRUE(row.spawned) << row.note;
    EXPECT_EQ(row.misaligned_starts, 0);
    EXPECT_GT(row.samples, 0);
    sum += row.mean_speed;
  }
  EXPECT_NEAR(sum / 4.0, 1.34, 0.134);
}

TEST(CrowdCheck, TheSocialForceIsFasterOneWayThanTwoWay) {
  // One-way flow: everyone walks counter-clockwise, nobody meets anyone head-on. The social force
  // slows a crowd only through counterflow (METHOD: one way it keeps its speed up to 1 /m²).
  FundamentalDiagramConfig config = SmallRing();
  config.duration = 2.0;
  config.crowd.model = sim::CrowdModel::kSocialForce;
  double two = 0.0, one = 0.0;
  for (std::uint64_t seed : {1, 2}) {
    two += RunDensity(config, CrowdFlow::kTwoWay, 1.0, seed, 0).mean_speed;
    one += RunDensity(config, CrowdFlow::kOneWay, 1.0, seed, 0).mean_speed;
  }
  EXPECT_GT(one, two);
  // The two flows share the lattice: the same people, only their directions differ.
  const auto a = RunDensity(config, CrowdFlow::kOneWay, 1.0, 1, 0);
  const auto b = RunDensity(config, CrowdFlow::kTwoWay, 1.0, 1, 0);
  EXPECT_EQ(a.count, b.count);
  EXPECT_EQ(a.lattice_spacing, b.lattice_spacing);
  EXPECT_THROW(ReadFundamentalDiagramConfig({"clockwise_fraction=0"}), core::ConfigError);
}

TEST(CrowdCheck, TheTtcCrowdSlowsDownWithDensityInBothFlows) {
  // A cheap version of the check (a small ring, 3 s of warm-up and 4 s measured, 1 and 3 /m²):
  // the anticipating crowd is markedly slower at 3 /m² than at 1 /m² whichever way it walks (the
  // social force one way is not), and within 25 % of Weidmann's speed at 1 /m².
  FundamentalDiagramConfig config = SmallRing();
  ASSERT_EQ(config.crowd.model, sim::CrowdModel::kTtc);
  for (CrowdFlow flow : {CrowdFlow::kOneWay, CrowdFlow::kTwoWay}) {
    const FundamentalDiagramRow low = RunDensity(config, flow, 1.0, 1, 0);
    const FundamentalDiagramRow high = RunDensity(config, flow, 3.0, 1, 1);
    ASSERT_TRUE(low.spawned && high.spawned);
    EXPECT_LT(high.mean_speed, 0.6 * low.mean_speed) << core::EnumName(flow);
    EXPECT_LT(std::abs(low.relative_deviation), 0.25) << core::EnumName(flow);
    EXPECT_GT(low.encounters, 0);
    // People pass each other without walking through each other.
    EXPECT_GT(low.closest_approach, 2.0 * config.pedestrian_radius);
    EXPECT_GT(high.closest_approach, 1.8 * config.pedestrian_radius);
  }
}

TEST(CrowdCheck, DeterministicPerSeed) {
  FundamentalDiagramConfig config = SmallRing();
  config.warmup = 1.0;
  config.duration = 2.0;
  const auto a = RunFundamentalDiagram(config, CrowdFlow::kTwoWay, {0.5, 1.5}, 7);
  const auto b = RunFundamentalDiagram(config, CrowdFlow::kTwoWay, {0.5, 1.5}, 7);
  const auto c = RunFundamentalDiagram(config, CrowdFlow::kTwoWay, {0.5, 1.5}, 8);
  ASSERT_EQ(a.rows.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(a.rows[i].mean_speed, b.rows[i].mean_speed);
    EXPECT_EQ(a.rows[i].speed_std, b.rows[i].speed_std);
    EXPECT_EQ(a.rows[i].closest_approach, b.rows[i].closest_approach);
  }
  EXPECT_NE(a.rows[1].mean_speed, c.rows[1].mean_speed);
}

TEST(CrowdCheck, ReportsADensityThatDoesNotFit) {
  FundamentalDiagramConfig config = SmallRing();
  config.pedestrian_radius = 0.3;  // hexagonal packing caps the density at 3.2 /m²
  const FundamentalDiagramRow row = RunDensity(config, CrowdFlow::kOneWay, 4.0, 1, 0);
  EXPECT_FALSE(row.spawned);
  EXPECT_NE(row.note.find("do not fit"), std::string::npos) << row.note;
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
