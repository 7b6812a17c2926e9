// Random looped tours: deterministic, as long as asked, on the grid's streets, never reversing,
// and revisiting themselves (what they are for).

#include "bench/worldgen/tour_generator.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bench/engine/switch_points.hpp"
#include "core/errors.hpp"

namespace retrace::bench {
namespace {

TEST(TourGenerator, IsDeterministicAndAsLongAsAsked) {
  TourConfig config;
  config.length = 900.0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const std::vector<core::Vec2> a = GenerateTour(config, seed);
    EXPECT_EQ(a, GenerateTour(config, seed));
    const double length = RouteLength(a);
    EXPECT_GE(length, 900.0);
    EXPECT_LT(length, 900.0 + 60.0 + 1e-9);  // it stops at the first crossing past it
  }
  EXPECT_NE(GenerateTour(config, 1), GenerateTour(config, 2));
}

TEST(TourGenerator, DrivesStreetsWithoutUTurnsAndRevisitsItself) {
  const TourConfig config;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const std::vector<core::Vec2> route = GenerateTour(config, seed);
    ASSERT_GE(route.size(), 3u);
    for (std::size_t i = 1; i < route.size(); ++i) {
      const core::Vec2 d = route[i] - route[i - 1];
      // Along a street: east-west or north-south.
      EXPECT_TRUE(std::abs(d.x()) < 1e-9 || std::abs(d.y()) < 1e-9) << "seed " << seed;
      EXPECT_GT(d.norm(), config.block_size[0] - 1e-9);
      if (i >= 2) {
        const core::Vec2 before = route[i - 1] - route[i - 2];
        EXPECT_GT(before.normalized().dot(d.normalized()), -0.5) << "U-turn, seed " << seed;
      }
    }
    // Loops come back to where they began: one map cannot hold it.
    EXPECT_FALSE(SuggestSwitchPoints(route, 5.0).empty()) << "seed " << seed;
  }
}

TEST(TourGenerator, RefusesBadSettings) {
  TourConfig config;
  config.block_size = {60.0, 30.0};
  EXPECT_THROW(GenerateTour(config, 1), core::ConfigError);
  config = TourConfig{};
  config.columns = 0;
  EXPECT_THROW(GenerateTour(config, 1), core::ConfigError);
  config = TourConfig{};
  config.length = 1e9;
  EXPECT_THROW(GenerateTour(config, 1), core::ConfigError);
}

}  // namespace
}  // namespace retrace::bench
