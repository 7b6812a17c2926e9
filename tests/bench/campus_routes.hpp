#pragma once
// Routes for the campus generator's tests: random drives, a route that crosses itself, a double
// loop; and the geometry of a generated world.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "sim/world_file.hpp"

namespace retrace::bench::testing_routes {

using core::Vec2;

// A random drive: straight runs of 20-50 m joined by turns of up to 120 degrees on arcs of
// 6 m radius. Long enough routes of this kind cross themselves now and then.
inline std::vector<Vec2> RandomRoute(std::uint64_t seed, int runs = 12) {
  core::Rng rng(seed);
  std::vector<Vec2> route{{0, 0}};
  double heading = 0.0;
  for (int i = 0; i < runs; ++i) {
    const double run = rng.Uniform(20.0, 50.0);
    route.push_back(route.back() + run * Vec2(std::cos(heading), std::sin(heading)));
    const double turn = rng.Uniform(-2.1, 2.1);
    constexpr double kRadius = 6.0;
    const int steps = std::max(1, static_cast<int>(std::abs(turn) / 0.26));
    for (int k = 1; k <= steps; ++k) {
      const double a = heading + turn * k / steps;
      const double a_prev = heading + turn * (k - 1) / steps;
      // Chord of the arc piece from a_prev to a.
      const double mid = 0.5 * (a + a_prev);
      const double chord = 2.0 * kRadius * std::sin(0.5 * std::abs(a - a_prev));
      route.push_back(route.back() + chord * Vec2(std::cos(mid), std::sin(mid)));
    }
    heading += turn;
  }
  return route;
}

// East 100 m, north, west, then south across the first leg at (50, 0), at right angles.
inline std::vector<Vec2> SelfCrossingRoute() {
  return {{0, 0}, {100, 0}, {100, 50}, {50, 50}, {50, -50}, {0, -50}};
}

// Twice round a 60 m x 40 m block: every stretch is driven twice.
inline std::vector<Vec2> DoubleLoop() {
  return {{0, 0}, {60, 0}, {60, 40}, {0, 40}, {0, 0}, {60, 0}, {60, 40}, {0, 40}, {0, 5}};
}

inline sim::StaticGeometry Geometry(const sim::WorldConfig& world) {
  return sim::BuildGeometry(world, {});
}

}  // namespace retrace::bench::testing_routes
