#pragma once
// An axis-aligned solid box, the wall or obstacle of most hand-built test worlds.

#include "sim/static_geometry.hpp"

namespace retrace::sim::test_geometry {

/// Adds the box [x0, x1] x [y0, y1] (m) to `g` as a polygon.
inline void AddBox(StaticGeometry& g, double x0, double y0, double x1, double y1) {
  g.AddPolygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

}  // namespace retrace::sim::test_geometry
