#pragma once
// Registering one partial map against another where their taught paths come back to the same
// place (the revisit edges of the route graph, nav/route_graph.hpp). The chain of switch poses
// already relates the two frames, but with the odometry drift of everything driven between the
// two visits; registration measures the transform that holds *at that place*, so that a robot
// moving between the two maps there is carried over without that drift.
//
// The occupied cells of map B within `radius` of the place (at most max_points of them, evenly
// thinned) are scored against map A's likelihood field (the localizer's own measurement model,
// nav/likelihood_field.hpp): a correlative search over a window around the chain's prior
// (translation and heading; coarse with 150 of the cells, then fine with all of them around the
// coarse best), then the best pose's share of cells that land within inlier_distance of A's
// walls. A match is refused when too few cells land on walls, or when a
// pose more than `ambiguity_distance` away scores nearly as well (a corridor seen along its
// axis, a row of identical rooms): a wrong edge would carry the robot to a wrong place, which is
// worse than no edge.

#include <optional>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "nav/likelihood_field.hpp"

namespace retrace::nav {

struct MapRegistrationConfig {
  double radius = 12.0;           ///< m around the place: map B's cells registered
  int max_points = 500;           ///< cells of B used, evenly thinned
  int min_points = 40;            ///< fewer occupied cells near the place: no registration
  double search_xy = 1.5;         ///< m: half-width of the translation window around the prior
  double search_theta = 0.1;      ///< rad: half-width of the heading window
  double coarse_xy = 0.2;         ///< m: coarse step (the fine search takes a quarter of it)
  double coarse_theta = 0.02;     ///< rad: coarse step
  double inlier_distance = 0.15;  ///< m: a cell of B this close to a wall of A is an inlier
  double min_inliers = 0.5;       ///< share of B's cells that must be inliers
  double ambiguity_distance = 1.0;  ///< m: another pose this far away ...
  double ambiguity_margin = 0.15;   ///< ... must have this much smaller an inlier share
};

/// An accepted registration.
struct MapRegistration {
  core::Pose2 X_AB;        ///< map B's frame in map A's
  double inliers = 0.0;    ///< share of B's cells within inlier_distance of A's walls
  /// the best inlier share of poses ambiguity_distance or more away, in the coarse search
  /// (inliers within inlier_distance + coarse_xy / √2, against the coarse best's)
  double runner_up = 0.0;
  int points = 0;          ///< B's cells used
};

/// Registers map B around the place p_B (in M_B) against map A's likelihood field, searching
/// around the prior X_AB. nullopt when refused (see above).
std::optional<MapRegistration> RegisterMaps(const LikelihoodField& field_A,
                                            const core::OccupancyGrid& grid_B,
                                            const core::Vec2& p_B, const core::Pose2& prior_X_AB,
                                            const MapRegistrationConfig& config);

}  // namespace retrace::nav
