#pragma once
// A procedural university campus around a route: buildings, hedges, rows of trees, poles and
// benches along both sides of the route (a polyline in W), stretches left deliberately bare
// (an open plaza or field, where the LiDAR sees next to nothing), and pedestrian groups
// walking along the route. The route always stays drivable: nothing comes closer than the
// corridor half-width to any route segment, including where the route crosses or revisits
// itself. Pure and deterministic: the same route, config and seed give the same world.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "core/pose2.hpp"
#include "sim/world_file.hpp"

namespace retrace::bench {

/// A [min, max] range of a random draw (uniform); min ≤ max.
using Range = std::array<double, 2>;

/// What to place and how densely. Lateral offsets are measured from the route's centre line
/// to the object's centre line (buildings: to their near face), in m. Densities count objects
/// (or rows, or hedges) per 100 m of route and per side; where the space is taken (crossings,
/// other objects, bare stretches) fewer are placed.
struct CampusConfig {
  std::string name = "campus";
  /// m of free space kept on both sides of every route segment: nothing comes closer. At least
  /// the robot radius (0.3 m) plus a 0.1 m margin.
  double corridor_half_width = 2.0;
  double object_gap = 0.5;  ///< m kept free between any two placed objects

  double buildings_per_100m = 3.0;
  /// m from the route to the near face; also the least distance to any route segment.
  Range building_setback{6.0, 12.0};
  Range building_width{10.0, 30.0};        ///< m along the route
  Range building_depth{8.0, 20.0};         ///< m across the route
  double building_l_shape_fraction = 0.3;  ///< share of L-shaped buildings (polygons)

  double hedges_per_100m = 1.5;
  Range hedge_offset{4.5, 7.0};     ///< m; hedges run behind the trees, following the route
  Range hedge_length{6.0, 25.0};    ///< m
  Range hedge_thickness{0.5, 1.0};  ///< m

  double tree_rows_per_100m = 2.0;
  Range tree_row_length{15.0, 50.0};  ///< m
  Range tree_offset{2.8, 4.5};        ///< m
  Range tree_spacing{4.0, 7.0};       ///< m between trees of a row
  Range tree_radius{0.15, 0.35};      ///< m (trunks at LiDAR height)

  double poles_per_100m = 3.0;
  Range pole_offset{2.3, 2.8};   ///< m (lamp posts, bollards, signs)
  Range pole_radius{0.05, 0.1};  ///< m

  double benches_per_100m = 1.5;
  Range bench_offset{2.6, 3.2};     ///< m
  core::Vec2 bench_size{1.6, 0.5};  ///< m along and across the route

  /// Landmark-poor stretches: no object is placed within landmark_poor_radius of the route
  /// anywhere along them. Given explicitly as arc-length intervals [from, to] (m), and/or as a
  /// fraction of the route covered by stretches of landmark_poor_length at seeded positions.
  std::vector<Range> landmark_poor_intervals;
  double landmark_poor_fraction = 0.0;
  double landmark_poor_length = 40.0;
  double landmark_poor_radius = 20.0;

  /// Pedestrians, split evenly into `wander_groups` groups wandering in squares of
  /// wander_region_size around points spread along the route, and `loop_groups` groups
  /// walking up and down stretches of loop_length of the route itself.
  int pedestrians = 20;
  int wander_groups = 3;
  int loop_groups = 2;
  double wander_region_size = 30.0;
  double loop_length = 60.0;

  template <class V>
  void Reflect(V& v) {
    v("name", name);
    v("corridor_half_width", corridor_half_width);
    v("object_gap", object_gap);
    v("buildings_per_100m", buildings_per_100m);
    v("building_setback", building_setback);
    v("building_width", building_width);
    v("building_depth", building_depth);
    v("building_l_shape_fraction", building_l_shape_fraction);
    v("hedges_per_100m", hedges_per_100m);
    v("hedge_offset", hedge_offset);
    v("hedge_length", hedge_length);
    v("hedge_thickness", hedge_thickness);
    v("tree_rows_per_100m", tree_rows_per_100m);
    v("tree_row_length", tree_row_length);
    v("tree_offset", tree_offset);
    v("tree_spacing", tree_spacing);
    v("tree_radius", tree_radius);
    v("poles_per_100m", poles_per_100m);
    v("pole_offset", pole_offset);
    v("pole_radius", pole_radius);
    v("benches_per_100m", benches_per_100m);
    v("bench_offset", bench_offset);
    v("bench_size", bench_size);
    v("landmark_poor_intervals", landmark_poor_intervals);
    v("landmark_poor_fraction", landmark_poor_fraction);
    v("landmark_poor_length", landmark_poor_length);
    v("landmark_poor_radius", landmark_poor_radius);
    v("pedestrians", pedestrians);
    v("wander_groups", wander_groups);
    v("loop_groups", loop_groups);
    v("wander_region_size", wander_region_size);
    v("loop_length", loop_length);
  }
  /// Throws core::ConfigError naming the key: negative densities, empty or reversed ranges,
  /// offsets inside the corridor, a corridor too narrow for the robot, bad intervals.
  void Validate() const;
};

/// What GenerateCampus placed, for summaries and tests.
struct CampusStats {
  int buildings = 0;  ///< boxes and L-shaped polygons
  int hedges = 0;     ///< thick walls
  int trees = 0;
  int poles = 0;
  int benches = 0;
  int pedestrian_groups = 0;
  double route_length = 0.0;                   ///< m
  std::vector<Range> landmark_poor_intervals;  ///< arc lengths (m) actually kept bare, sorted
};

/// Generates the campus around `route` (W, m). Throws core::ConfigError on an invalid config
/// or a landmark-poor interval that starts beyond the end of the route, and core::WorldError
/// on a route with fewer than 2 distinct points or non-finite points.
/// `stats`, if given, receives the counts of what was placed.
sim::WorldConfig GenerateCampus(const std::vector<core::Vec2>& route, const CampusConfig& config,
                                std::uint64_t seed, CampusStats* stats = nullptr);

}  // namespace retrace::bench
