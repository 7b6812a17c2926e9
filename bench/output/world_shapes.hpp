#pragma once
// The world's static geometry as the figures draw it (viz has no sim types).

#include "sim/static_geometry.hpp"
#include "viz/figure_data.hpp"

namespace retrace::bench {

/// Solids as filled polygons, circles as discs, and the edges that outline no polygon (walls of
/// imported maps) as thin segments.
viz::WorldShapes WorldShapesOf(const sim::StaticGeometry& geometry);

}  // namespace retrace::bench
