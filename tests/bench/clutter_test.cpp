// Unmapped clutter (bench/engine/clutter.hpp): density over a long route, the corridor and the
// geometry kept free, deterministic per seed, off at density 0, and bad input as one clear error.

#include "bench/engine/clutter.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/nearest_grid.hpp"
#include "core/rng.hpp"
#include "sim/world_file.hpp"

namespace retrace::bench::clutter_test {

using core::Vec2;

// A 420 m route: out along y = 0, a turn, back along y = 20; a wall of 1 m boxes every 10 m
// at 2 m beside the outward leg, so that some of the band is taken.
struct Site {
  std::vector<Vec2> route{{0.0, 0.0}, {200.0, 0.0}, {200.0, 20.0}, {0.0, 20.0}};
  sim::StaticGeometry geometry;
  Site() {
    for (int i = 0; i < 20; ++i) {
      const double x = 5.0 + 10.0 * i;
      geometry.AddPolygon({{x, 2.0}, {x + 1.0, 2.0}, {x + 1.0, 3.0}, {x, 3.0}});
    }
  }
  ClutterSite Of() const { return {&route, &geometry, 0.3, 2.5}; }
};

ClutterConfig Config(double density, double standing) {
  ClutterConfig c;
  c.density = density;
  c.standing_density = standing;
  return c;
}

// Every footprint as a solid (boxes as rings, bins as circles).
sim::StaticGeometry Solids(const Clutter& clutter) {
  sim::StaticGeometry g;
  for (const auto& b : clutter.boxes) g.AddPolygon(sim::BoxRing(b));
  for (const auto& c : clutter.circles) g.AddCircle({c.center, c.radius});
  return g;
}

TEST(Clutter, DensityMatchesTheAskedOneOverALongRoute) {
  const Site site;
  for (std::uint64_t seed : {1, 2, 3}) {
    const Clutter c = GenerateClutter(Config(0.05, 0.01), site.Of(), core::Rng(seed));
    // The band's free area: both sides of 420 m, from 0.6 m to 3 m (2016 m²), less the boxes'
    // share, plus the caps at the ends and the outer corners (about 40 m²).
    EXPECT_GT(c.band_area, 0.9 * 2016.0);
    EXPECT_LT(c.band_area, 2016.0 + 60.0);
    const double objects = static_cast<double>(c.boxes.size() + c.circles.size());
    EXPECT_NEAR(objects / c.band_area, 0.05, 0.001);
    EXPECT_NEAR(static_cast<double>(c.standing.size()) / c.band_area, 0.01, 0.001);
  }
}

TEST(Clutter, NothingInTheCorridorOrInGeometryOrOnOtherClutter) {
  const Site site;
  const ClutterConfig config = Config(0.08, 0.02);
  const double corridor = 0.3 + config.clearance;
  const core::PolylineDistance route_distance(site.route);
  for (std::uint64_t seed : {1, 2, 3, 4}) {
    const Clutter c = GenerateClutter(config, site.Of(), core::Rng(seed));
    const sim::StaticGeometry solids = Solids(c);
    // Every corner of every box and the rim of every circle outside the corridor.
    for (const auto& b : c.boxes) {
      for (const Vec2& q : sim::BoxRing(b)) EXPECT_GE(route_distance(q), corridor);
      EXPECT_GE(site.geometry.Clearance(b.center), 0.5 * b.size.norm());
      EXPECT_LE(route_distance(b.center), config.band);
    }
    for (const auto& circle : c.circles) {
      EXPECT_GE(route_distance(circle.center) - circle.radius, corridor);
      EXPECT_GE(site.geometry.Clearance(circle.center), circle.radius);
    }
    for (const Vec2& p : c.standing) {
      EXPECT_GE(route_distance(p) - config.person_radius, corridor);
      EXPECT_GE(site.geometry.Clearance(p), config.person_radius + 0.5);
      EXPECT_GE(solids.Clearance(p), config.person_radius);
    }
    // No two objects overlap: no corner of one inside another.
    for (std::size_t i = 0; i < c.boxes.size(); ++i) {
      for (std::size_t j = 0; j < c.boxes.size(); ++j) {
        if (i == j) continue;
        sim::StaticGeometry other;
        other.AddPolygon(sim::BoxRing(c.boxes[j]));
        for (const Vec2& q : sim::BoxRing(c.boxes[i])) EXPECT_FALSE(other.IsInside(q));
      }
    }
  }
}

TEST(Clutter, SameSeedSameClutterOtherSeedOther) {
  const Site site;
  const Clutter a = GenerateClutter(Config(0.03, 0.01), site.Of(), core::Rng(7).Split("clutter"));
  const Clutter b = GenerateClutter(Config(0.03, 0.01), site.Of(), core::Rng(7).Split("clutter"));
  const Clutter c = GenerateClutter(Config(0.03, 0.01), site.Of(), core::Rng(8).Split("clutter"));
  ASSERT_EQ(a.boxes.size(), b.boxes.size());
  for (std::size_t i = 0; i < a.boxes.size(); ++i) {
    EXPECT_EQ(a.boxes[i].center, b.boxes[i].center);
    EXPECT_EQ(a.boxes[i].yaw, b.boxes[i].yaw);
  }
  EXPECT_EQ(a.standing, b.standing);
  EXPECT_NE(a.standing, c.standing);
  EXPECT_NE(a.boxes.front().center, c.boxes.front().center);
}

TEST(Clutter, ZeroDensityPlacesNothing) {
  const Site site;
  const Clutter c = GenerateClutter(Config(0.0, 0.0), site.Of(), core::Rng(1));
  EXPECT_TRUE(c.boxes.empty());
  EXPECT_TRUE(c.circles.empty());
  EXPECT_TRUE(c.standing.empty());
  // Only people: no objects.
  const Clutter people = GenerateClutter(Config(0.0, 0.01), site.Of(), core::Rng(1));
  EXPECT_TRUE(people.boxes.empty() && people.circles.empty());
  EXPECT_FALSE(people.standing.empty());
}

TEST(Clutter, KindsHaveTheirFootprints) {
  const Site site;
  ClutterConfig config = Config(0.03, 0.0);
  config.kinds = {ClutterKind::kBin};
  const Clutter bins = GenerateClutter(config, site.Of(), core::Rng(1));
  EXPECT_TRUE(bins.boxes.empty());
  ASSERT_FALSE(bins.circles.empty());
  EXPECT_DOUBLE_EQ(bins.circles.front().radius, 0.2);
  config.kinds = {ClutterKind::kBike};
  const Clutter bikes = GenerateClutter(config, site.Of(), core::Rng(1));
  ASSERT_FALSE(bikes.boxes.empty());
  EXPECT_EQ(bikes.boxes.front().size, Vec2(1.8, 0.6));
}

TEST(Clutter, TooDenseIsOneErrorNamingTheKey) {
  const Site site;
  try {
    GenerateClutter(Config(0.9, 0.0), site.Of(), core::Rng(1));
    FAIL() << "no error";
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "density");
    EXPECT_THAT(e.what(), ::testing::HasSubstr("fit beside the route"));
  }
  ClutterConfig crowded = Config(0.0, 1.0);
  crowded.person_radius = 0.5;
  try {
    GenerateClutter(crowded, site.Of(), core::Rng(1));
    FAIL() << "no error";
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "standing_density");
  }
}

TEST(Clutter, BadKeysAreRefused) {
  EXPECT_THROW(Config(-0.1, 0.0).Validate(), core::ConfigError);
  EXPECT_THROW(Config(0.0, -0.1).Validate(), core::ConfigError);
  ClutterConfig twice = Config(0.1, 0.0);
  twice.kinds = {ClutterKind::kChair, ClutterKind::kChair};
  EXPECT_THROW(twice.Validate(), core::ConfigError);
  // A band inside the corridor holds nothing.
  const Site site;
  ClutterConfig narrow = Config(0.1, 0.0);
  narrow.band = 0.5;
  try {
    GenerateClutter(narrow, site.Of(), core::Rng(1));
    FAIL() << "no error";
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "band");
  }
}

}  // namespace retrace::bench::clutter_test
