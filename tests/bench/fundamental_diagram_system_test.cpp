// The crowd check's simulations (bench/crowd/fundamental_diagram.hpp, `retrace crowd-check`):
// short runs of both flows and both crowd models in a small ring, determinism per seed and a
// density that does not fit (system tier: a minute under the sanitizers, seconds in Release).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "bench/crowd/crowd_check.hpp"
#include "bench/crowd/fundamental_diagram.hpp"
#include "core/config.hpp"
#include "core/errors.hpp"

namespace retrace::bench {
namespace {

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
  // slows a crowd only through counterflow (docs/CROWD.md: one way it keeps its speed up to 1 /m²).
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

}  // namespace
}  // namespace retrace::bench
