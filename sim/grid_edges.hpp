#pragma once
// Turns an occupancy grid (an imported ROS map) into static geometry: the faces between
// occupied and non-occupied cells, merged into maximal straight runs, as two-sided edges.
// Merging matters: one edge per cell face would make ray casting and physics several times
// slower (anchors.md: 1.8 M vs 0.5 M Box2D rays/s).

#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/rng.hpp"
#include "sim/static_geometry.hpp"

namespace retrace::sim {

/// Cells whose occupancy probability is at least `occupied_threshold` become solid; unknown and
/// free cells, and everything outside the grid, are open. Returns the mask of solid cells.
OccupancyMask OccupiedMask(const core::OccupancyGrid& grid, double occupied_threshold);

/// Makes each unknown cell of `grid` (below `occupied_threshold`, not known free) solid in
/// *mask with probability 1 − exp(−π r / (4 free_path)), r the resolution: rays in uniformly
/// random directions then travel `free_path` (m) through unknown cells on average before they
/// meet a solid one. One draw per unknown cell, in row-major order, from `rng`.
void FillUnknownCells(const core::OccupancyGrid& grid, double occupied_threshold, double free_path,
                      core::Rng rng, OccupancyMask* mask);

/// The merged boundary faces of the solid cells of `mask`, in W.
std::vector<Segment> MergedBoundaryEdges(const OccupancyMask& mask);

}  // namespace retrace::sim
