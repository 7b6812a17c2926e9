// Random looped tours: deterministic, as long as asked, on the grid's streets, never reversing,
// and revisiting themselves (what they are for).

#include "bench/worldgen/tour_generator.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bench/engine/switch_points.hpp"
#include "core/errors.hpp"
#include "io/route_file.hpp"

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

TEST(TourGenerator, TheShippedTourIsStillWhatItsCommandWrote) {
  // scenarios/tour/route.txt: `retrace generate-tour --seed 1 --set length=1600`.
  TourConfig config;
  config.length = 1600.0;
  const std::vector<core::Vec2> route = GenerateTour(config, 1);
  const std::vector<core::Vec2> shipped =
      io::ReadRouteFile(std::string(RETRACE_SOURCE_DIR) + "/scenarios/tour/route.txt");
  ASSERT_EQ(route.size(), shipped.size());
  for (std::size_t i = 0; i < route.size(); ++i) EXPECT_LT((route[i] - shipped[i]).norm(), 1e-3);
}

TEST(TourGenerator, OutAndBackLegsComeStraightBackAlongTheirStreets) {
  TourConfig config;
  config.out_and_back = 3;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const std::vector<core::Vec2> route = GenerateTour(config, seed);
    int u_turns = 0;
    for (std::size_t i = 2; i < route.size(); ++i) {
      const core::Vec2 before = route[i - 1] - route[i - 2];
      const core::Vec2 d = route[i] - route[i - 1];
      if (before.normalized().dot(d.normalized()) < -0.99) {
        ++u_turns;
        // Back along the same street, at least as far as it went out when it turns again.
        EXPECT_GE(d.norm(), config.block_size[0] - 1e-9) << "seed " << seed;
      }
    }
    EXPECT_GE(u_turns, 1) << "seed " << seed;
    EXPECT_LE(u_turns, 3) << "seed " << seed;
  }
  config.out_and_back = -1;
  EXPECT_THROW(GenerateTour(config, 1), core::ConfigError);
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
