// Generated campuses keep the whole corridor along random, self-crossing and revisiting routes
// free, with the default and a three times denser furnishing (system tier: 24 worlds).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "bench/cli/campus_command.hpp"
#include "bench/engine/switch_points.hpp"
#include "bench/worldgen/campus_generator.hpp"
#include "core/config.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "io/config_yaml.hpp"
#include "io/route_file.hpp"
#include "sim/pedestrians.hpp"
#include "sim/physics_world.hpp"
#include "sim/route_check.hpp"
#include "sim/world_file.hpp"
#include "tests/bench/campus_routes.hpp"
#include "tests/support/config_key.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
namespace {

using namespace testing_routes;

TEST(CampusGenerator, RouteStaysDrivableIncludingWhereItCrossesOrRevisitsItself) {
  std::vector<std::vector<Vec2>> routes{SelfCrossingRoute(), DoubleLoop()};
  for (std::uint64_t r = 20; r < 24; ++r) routes.push_back(RandomRoute(r, 20));
  CampusConfig dense;
  dense.buildings_per_100m *= 3;
  dense.hedges_per_100m *= 3;
  dense.tree_rows_per_100m *= 3;
  dense.poles_per_100m *= 3;
  dense.benches_per_100m *= 3;
  for (std::size_t i = 0; i < routes.size(); ++i) {
    for (const CampusConfig& config : {CampusConfig{}, dense}) {
      for (std::uint64_t seed : {1, 2}) {
        const sim::StaticGeometry g = Geometry(GenerateCampus(routes[i], config, seed));
        // The whole corridor is free, not only the robot's footprint.
        EXPECT_NO_THROW(sim::CheckRouteIsDrivable(g, routes[i], config.corridor_half_width - 1e-3))
            << "route " << i << " seed " << seed;
      }
    }
  }
}

}  // namespace
}  // namespace retrace::bench
