#include "bench/worldgen/campus_generator.hpp"

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
#include "core/config.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "core/segment.hpp"
#include "io/config_yaml.hpp"
#include "io/route_file.hpp"
#include "sim/pedestrians.hpp"
#include "sim/physics_world.hpp"
#include "sim/route_check.hpp"
#include "sim/world_file.hpp"
#include "tests/bench/campus_routes.hpp"
#include "tests/support/config_key.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
namespace {

using namespace testing_routes;

using core::Vec2;
using ::testing::HasSubstr;

using retrace::testing::kSource;
const std::vector<std::uint64_t> kSeeds{1, 2, 3, 4};

double DistanceToRoute(const std::vector<Vec2>& route, const Vec2& p) {
  double best = 1e9;
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    best = std::min(best, core::SegmentDistance(p, route[i], route[i + 1]));
  }
  return best;
}

int Objects(const CampusStats& s) { return s.buildings + s.hedges + s.trees + s.poles + s.benches; }

// Nearest static geometry to the route between arc lengths s0 and s1, sampled every 0.5 m.
double MinClearanceAlong(const sim::StaticGeometry& g, const std::vector<Vec2>& route, double s0,
                         double s1) {
  double best = 1e9;
  double s_at = 0.0;
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    const double len = (route[i + 1] - route[i]).norm();
    for (double t = 0.0; t < len; t += 0.5) {
      const double s = s_at + t;
      if (s >= s0 && s <= s1)
        best = std::min(best, g.Clearance(route[i] + (route[i + 1] - route[i]) * (t / len)));
    }
    s_at += len;
  }
  return best;
}

TEST(CampusGenerator, SameRouteConfigAndSeedGiveTheSameWorld) {
  const auto route = RandomRoute(11);
  const CampusConfig config;
  const std::string a = io::ConfigToYaml(GenerateCampus(route, config, 7));
  EXPECT_EQ(a, io::ConfigToYaml(GenerateCampus(route, config, 7)));
  EXPECT_NE(a, io::ConfigToYaml(GenerateCampus(route, config, 8)));
}

TEST(CampusGenerator, PlacesEveryKindOfObjectOnBothSides) {
  const auto route = RandomRoute(5);
  CampusStats stats;
  const sim::WorldConfig world = GenerateCampus(route, CampusConfig{}, 3, &stats);
  EXPECT_GT(stats.buildings, 0);
  EXPECT_GT(stats.hedges, 0);
  EXPECT_GT(stats.trees, 0);
  EXPECT_GT(stats.poles, 0);
  EXPECT_GT(stats.benches, 0);
  EXPECT_EQ(world.boxes.size() + world.polygons.size(),
            static_cast<std::size_t>(stats.buildings + stats.benches));
  EXPECT_EQ(world.circles.size(), static_cast<std::size_t>(stats.trees + stats.poles));
  EXPECT_EQ(world.walls.size(), static_cast<std::size_t>(stats.hedges));
  EXPECT_NEAR(stats.route_length, RouteLength(route), 1e-9);
  // Both sides: as many objects to the left of the direction of travel as to the right, give
  // or take, judged by the first segment's side for objects near it.
  int left = 0, right = 0;
  for (const auto& c : world.circles) {
    for (std::size_t i = 0; i + 1 < route.size(); ++i) {
      const Vec2 d = route[i + 1] - route[i];
      const double t = (c.center - route[i]).dot(d) / d.squaredNorm();
      if (t < 0.0 || t > 1.0) continue;
      const Vec2 rel = c.center - (route[i] + t * d);
      if (rel.norm() > 6.0) continue;
      (d.x() * rel.y() - d.y() * rel.x() > 0.0 ? left : right)++;
      break;
    }
  }
  EXPECT_GT(left, 10);
  EXPECT_GT(right, 10);
}

TEST(CampusGenerator, NarrowerCorridorKeepsItsWidth) {
  CampusConfig config;
  config.corridor_half_width = 0.45;
  config.pole_offset = {0.5, 0.6};
  config.tree_offset = {0.8, 1.0};
  config.bench_offset = {0.8, 1.0};
  config.hedge_offset = {1.0, 1.5};
  config.building_setback = {2.0, 4.0};
  for (std::uint64_t seed : kSeeds) {
    const sim::StaticGeometry g = Geometry(GenerateCampus(SelfCrossingRoute(), config, seed));
    EXPECT_NO_THROW(sim::CheckRouteIsDrivable(g, SelfCrossingRoute(), 0.449)) << seed;
    EXPECT_THROW(sim::CheckRouteIsDrivable(g, SelfCrossingRoute(), 3.0), core::WorldError) << seed;
  }
}

TEST(CampusGenerator, DensityScalesTheNumberOfObjects) {
  const auto route = RandomRoute(7, 16);
  CampusConfig sparse;
  sparse.buildings_per_100m = 1.0;
  sparse.hedges_per_100m = 0.5;
  sparse.tree_rows_per_100m = 0.5;
  sparse.poles_per_100m = 1.0;
  sparse.benches_per_100m = 0.5;
  CampusConfig twice = sparse;
  twice.buildings_per_100m *= 2;
  twice.hedges_per_100m *= 2;
  twice.tree_rows_per_100m *= 2;
  twice.poles_per_100m *= 2;
  twice.benches_per_100m *= 2;
  CampusConfig none = sparse;
  none.buildings_per_100m = none.hedges_per_100m = none.tree_rows_per_100m = 0.0;
  none.poles_per_100m = none.benches_per_100m = 0.0;
  CampusStats a_sum, b_sum;
  for (std::uint64_t seed : kSeeds) {
    CampusStats a, b, z;
    GenerateCampus(route, sparse, seed, &a);
    GenerateCampus(route, twice, seed, &b);
    GenerateCampus(route, none, seed, &z);
    EXPECT_EQ(Objects(z), 0);
    a_sum.buildings += a.buildings;
    b_sum.buildings += b.buildings;
    a_sum.trees += a.trees;
    b_sum.trees += b.trees;
    a_sum.poles += a.poles;
    b_sum.poles += b.poles;
    a_sum.benches += a.benches;
    b_sum.benches += b.benches;
    a_sum.hedges += a.hedges;
    b_sum.hedges += b.hedges;
  }
  // Some proposals are rejected (crossings, other objects), more so when crowded.
  EXPECT_GT(b_sum.buildings, 1.5 * a_sum.buildings);
  EXPECT_GT(b_sum.trees, 1.5 * a_sum.trees);
  EXPECT_GT(b_sum.poles, 1.5 * a_sum.poles);
  EXPECT_GT(b_sum.benches, 1.5 * a_sum.benches);
  EXPECT_GT(b_sum.hedges, 1.3 * a_sum.hedges);
}

TEST(CampusGenerator, LandmarkPoorStretchHasNothingWithinTheRadius) {
  const auto route = RandomRoute(9, 14);
  CampusConfig config;
  config.landmark_poor_intervals = {{120.0, 170.0}};
  config.landmark_poor_radius = 15.0;
  for (std::uint64_t seed : kSeeds) {
    CampusStats stats;
    const sim::StaticGeometry bare = Geometry(GenerateCampus(route, config, seed, &stats));
    ASSERT_EQ(stats.landmark_poor_intervals.size(), 1u);
    EXPECT_GE(MinClearanceAlong(bare, route, 120.0, 170.0), 15.0 - 1e-6) << seed;
    // Without it the same stretch has things within a few metres.
    const sim::StaticGeometry normal = Geometry(GenerateCampus(route, CampusConfig{}, seed));
    EXPECT_LT(MinClearanceAlong(normal, route, 120.0, 170.0), 5.0) << seed;
  }
}

TEST(CampusGenerator, LandmarkPoorIntervalPastTheEndOfTheRouteIsAnError) {
  CampusConfig config;
  config.landmark_poor_intervals = {{10.0, 30.0}, {400.0, 450.0}};
  try {
    GenerateCampus(SelfCrossingRoute(), config, 1);  // 350 m
    FAIL() << "expected a ConfigError";
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "landmark_poor_intervals[1]");
    EXPECT_THAT(e.what(), HasSubstr("beyond the end of the route (350 m)"));
  }
  // An interval running over the end is cut at the end.
  config.landmark_poor_intervals = {{300.0, 450.0}};
  CampusStats stats;
  GenerateCampus(SelfCrossingRoute(), config, 1, &stats);
  ASSERT_EQ(stats.landmark_poor_intervals.size(), 1u);
  EXPECT_EQ(stats.landmark_poor_intervals[0], (Range{300.0, 350.0}));
}

TEST(CampusGenerator, LandmarkPoorFractionCoversThatShareOfTheRoute) {
  const auto route = RandomRoute(4, 20);
  const double length = RouteLength(route);
  CampusConfig config;
  config.landmark_poor_fraction = 0.2;
  config.landmark_poor_length = 40.0;
  for (std::uint64_t seed : kSeeds) {
    CampusStats stats;
    const sim::StaticGeometry g = Geometry(GenerateCampus(route, config, seed, &stats));
    double covered = 0.0;
    for (const Range& r : stats.landmark_poor_intervals) {
      covered += r[1] - r[0];
      EXPECT_GE(MinClearanceAlong(g, route, r[0], r[1]), config.landmark_poor_radius - 1e-6);
    }
    EXPECT_GE(covered, 0.2 * length - 1e-6) << seed;
    EXPECT_LT(covered, 0.2 * length + 40.0) << seed;
  }
}

TEST(CampusGenerator, PedestriansAreSplitIntoGroupsThatSpawnInTheWorld) {
  const auto route = RandomRoute(3, 10);
  CampusConfig config;
  config.pedestrians = 17;
  config.wander_groups = 2;
  config.loop_groups = 2;
  const sim::WorldConfig world = GenerateCampus(route, config, 5);
  int total = 0, loops = 0;
  for (const auto& g : world.pedestrians) {
    EXPECT_NO_THROW(g.Validate());
    total += g.count;
    if (g.mode == sim::PedestrianMode::kLoop) {
      ++loops;
      // Loop groups walk along the route itself.
      for (const Vec2& w : g.waypoints) EXPECT_LT(DistanceToRoute(route, w), 0.01);
    }
  }
  EXPECT_EQ(total, 17);
  EXPECT_EQ(loops, 2);
  EXPECT_EQ(world.pedestrians.size(), 4u);

  const sim::StaticGeometry g = Geometry(world);
  sim::PhysicsWorld physics(g);
  const sim::Pedestrians crowd(world.pedestrians, sim::CrowdConfig{}, g, core::Rng(1),
                               {{route.front(), 0.3}}, physics);
  EXPECT_EQ(crowd.size(), 17);

  config.pedestrians = 0;
  EXPECT_TRUE(GenerateCampus(route, config, 5).pedestrians.empty());
}

TEST(CampusGenerator, RejectsARouteWithoutTwoDistinctPoints) {
  EXPECT_THROW(GenerateCampus({{1, 1}}, CampusConfig{}, 1), core::WorldError);
  EXPECT_THROW(GenerateCampus({{1, 1}, {1, 1}}, CampusConfig{}, 1), core::WorldError);
  EXPECT_THROW(GenerateCampus({{0, 0}, {std::nan(""), 1}}, CampusConfig{}, 1), core::WorldError);
}

TEST(CampusConfig, ValidateNamesTheOffendingKey) {
  using retrace::testing::ValidationErrorKey;
  EXPECT_EQ(ValidationErrorKey(CampusConfig{}), retrace::testing::kValid);
  EXPECT_EQ(ValidationErrorKey<CampusConfig>([](auto& c) { c.corridor_half_width = 0.3; }),
            "corridor_half_width");
  EXPECT_EQ(ValidationErrorKey<CampusConfig>([](auto& c) {
              c.pole_offset = {1.0, 2.5};
            }),
            "pole_offset");
  EXPECT_EQ(ValidationErrorKey<CampusConfig>([](auto& c) {
              c.tree_radius = {0.3, 0.1};
            }),
            "tree_radius");
  EXPECT_EQ(ValidationErrorKey<CampusConfig>([](auto& c) { c.poles_per_100m = -1; }),
            "poles_per_100m");
  EXPECT_EQ(ValidationErrorKey<CampusConfig>([](auto& c) {
              c.landmark_poor_intervals = {{5, 50}, {60, 40}};
            }),
            "landmark_poor_intervals[1]");
  EXPECT_EQ(ValidationErrorKey<CampusConfig>([](auto& c) { c.landmark_poor_fraction = 0.9; }),
            "landmark_poor_fraction");
  EXPECT_EQ(ValidationErrorKey<CampusConfig>([](auto& c) {
              c.wander_groups = 0;
              c.loop_groups = 0;
            }),
            "wander_groups");
  EXPECT_EQ(ValidationErrorKey<CampusConfig>([](auto& c) { c.pedestrians = -2; }), "pedestrians");
}

// ---- retrace generate-campus -------------------------------------------------------------------

using GenerateCampusCommand = retrace::testing::TempDirTest;

std::string RouteText(const std::vector<Vec2>& route) {
  std::string text = "# test route\n";
  for (const Vec2& p : route)
    text += core::FormatNumber(p.x()) + " " + core::FormatNumber(p.y()) + "\n";
  return text;
}

TEST_F(GenerateCampusCommand, WritesAWorldThatLoadsBackWithItsCommandInTheHeader) {
  GenerateCampusOptions options;
  options.route_file = tmp_.Write("route.txt", RouteText(SelfCrossingRoute()));
  options.out = tmp_.path() / "worlds" / "campus.yaml";
  options.seed = 3;
  options.pedestrians = 12;
  options.overrides = {"landmark_poor_intervals=[[20, 60]]", "name=test campus"};
  const std::string summary = GenerateCampusWorld(options);
  EXPECT_THAT(summary, HasSubstr("buildings"));
  EXPECT_THAT(summary, HasSubstr("trees"));
  EXPECT_THAT(summary, HasSubstr("(12 pedestrians)"));
  EXPECT_THAT(summary, HasSubstr("350 m route"));
  EXPECT_THAT(summary, HasSubstr("landmark-poor stretches: 20-60 m"));

  const sim::World world = sim::LoadWorld(options.out);
  EXPECT_EQ(world.config.name, "test campus");
  EXPECT_NO_THROW(sim::CheckRouteIsDrivable(world.geometry, SelfCrossingRoute(), 0.3));
  const std::string text = tmp_.Read(options.out);
  EXPECT_EQ(text.rfind("# Campus world generated by `retrace generate-campus`", 0), 0u);
  EXPECT_THAT(
      text,
      HasSubstr("--seed 3 --set 'landmark_poor_intervals=[[20, 60]]' --set 'name=test campus' "
                "--pedestrians 12\n"));
  // The same command writes the same bytes.
  const std::string first = text;
  GenerateCampusWorld(options);
  EXPECT_EQ(tmp_.Read(options.out), first);
}

TEST_F(GenerateCampusCommand, ReadsSettingsFromAConfigFileWithOverridesOnTop) {
  GenerateCampusOptions options;
  options.route_file = tmp_.Write("route.txt", RouteText(DoubleLoop()));
  options.config_file = tmp_.Write("campus.yaml", "pedestrians: 4\nposes_per_100m: 1\n");
  options.out = tmp_.path() / "world.yaml";
  try {
    GenerateCampusWorld(options);
    FAIL() << "expected a ConfigError";
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("campus.yaml:2"));
    EXPECT_THAT(e.what(), HasSubstr("did you mean 'poles_per_100m'"));
  }
  EXPECT_FALSE(std::filesystem::exists(options.out));

  options.config_file =
      tmp_.Write("campus.yaml", "pedestrians: 4\npoles_per_100m: 0\nbenches_per_100m: 0\n");
  options.overrides = {"benches_per_100m=2"};
  const std::string summary = GenerateCampusWorld(options);
  EXPECT_THAT(summary, HasSubstr(" 0 poles"));
  EXPECT_THAT(summary, ::testing::Not(HasSubstr(" 0 benches")));
  EXPECT_THAT(summary, HasSubstr("(4 pedestrians)"));
}

TEST_F(GenerateCampusCommand, BadInputWritesNothing) {
  GenerateCampusOptions options;
  options.out = tmp_.path() / "world.yaml";
  options.route_file = tmp_.path() / "missing.txt";
  EXPECT_THROW(GenerateCampusWorld(options), core::IoError);

  options.route_file = tmp_.Write("one.txt", "1 2\n");
  EXPECT_THROW(GenerateCampusWorld(options), core::IoError);

  options.route_file = tmp_.Write("route.txt", RouteText(DoubleLoop()));
  options.overrides = {"no_such_key=1"};
  try {
    GenerateCampusWorld(options);
    FAIL() << "expected a ConfigError";
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no_such_key"));
    EXPECT_THAT(e.what(), HasSubstr("unknown key"));
  }
  options.overrides = {"corridor_half_width=0.1"};
  EXPECT_THROW(GenerateCampusWorld(options), core::ConfigError);
  options.overrides = {};
  options.config_file = tmp_.path() / "missing.yaml";
  EXPECT_THROW(GenerateCampusWorld(options), core::IoError);
  EXPECT_FALSE(std::filesystem::exists(options.out));
}

TEST(GenerateCampusOptions, ParseFromTheCommandLine) {
  CLI::App app;
  GenerateCampusOptions options;
  AddGenerateCampusOptions(app.add_subcommand("generate-campus"), &options);
  app.parse("generate-campus r.txt --set a=1 --set b=[1,2] --out w.yaml --seed 5 --pedestrians 7",
            false);
  EXPECT_EQ(options.route_file, "r.txt");
  EXPECT_EQ(options.out, "w.yaml");
  EXPECT_EQ(options.seed, 5u);
  EXPECT_EQ(options.pedestrians, 7);
  EXPECT_THAT(options.overrides, ::testing::ElementsAre("a=1", "b=[1,2]"));
  EXPECT_TRUE(options.config_file.empty());

  CLI::App strict;
  GenerateCampusOptions other;
  AddGenerateCampusOptions(strict.add_subcommand("generate-campus"), &other);
  EXPECT_THROW(strict.parse("generate-campus r.txt", false), CLI::ParseError);  // no --out
  strict.parse("generate-campus --set a=1 r.txt --out w.yaml", false);
  EXPECT_EQ(other.route_file, "r.txt");
  EXPECT_THAT(other.overrides, ::testing::ElementsAre("a=1"));
}

// The shipped campus: drivable, and exactly what its header's command generates.
TEST(ShippedCampus, WorldIsDrivableAndReproducibleFromItsHeaderCommand) {
  const auto route = io::ReadRouteFile(kSource / "worlds/routes/campus.txt");
  const sim::World world = sim::LoadWorld(kSource / "worlds/campus.yaml");
  EXPECT_NO_THROW(sim::CheckRouteIsDrivable(world.geometry, route, 0.3));
  std::ifstream in(kSource / "worlds/campus.yaml", std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string command =
      "retrace generate-campus worlds/routes/campus.txt --out worlds/campus.yaml --seed 2018 "
      "--set 'landmark_poor_intervals=[[680, 725]]' --pedestrians 30";
  EXPECT_THAT(text, HasSubstr("#   " + command + "\n"));

  CampusConfig config;
  config.landmark_poor_intervals = {{680.0, 725.0}};
  config.pedestrians = 30;
  CampusStats stats;
  const std::string yaml = io::ConfigToYaml(GenerateCampus(route, config, 2018, &stats));
  ASSERT_GE(text.size(), yaml.size());
  EXPECT_EQ(text.substr(text.size() - yaml.size()), yaml)
      << "worlds/campus.yaml is out of date: regenerate it with the command in its header";
  EXPECT_GE(stats.route_length, 600.0);
  EXPECT_LE(stats.route_length, 1000.0);
  EXPECT_GE(MinClearanceAlong(world.geometry, route, 680.0, 725.0), 15.0 - 1e-6);
}

}  // namespace
}  // namespace retrace::bench
