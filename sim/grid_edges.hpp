#pragma once
// Turns an occupancy grid (an imported ROS map) into static geometry: the faces between
// occupied and non-occupied cells, merged into maximal straight runs, as two-sided edges.
// Merging matters: one edge per cell face would make ray casting and physics several times
// slower (anchors.md: 1.8 M vs 0.5 M Box2D rays/s).

#include <vector>

#include "core/occupancy_grid.hpp"
#include "sim/static_geometry.hpp"

namespace retrace::sim {

/// Cells whose occupancy probability is at least `occupied_threshold` become solid; unknown and
/// free cells, and everything outside the grid, are open. Returns the mask of solid cells.
OccupancyMask OccupiedMask(const core::OccupancyGrid& grid, double occupied_threshold);

/// The merged boundary faces of the solid cells of `mask`, in W.
std::vector<Segment> MergedBoundaryEdges(const OccupancyMask& mask);

}  // namespace retrace::sim
