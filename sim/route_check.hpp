#pragma once

#include <vector>

#include "sim/static_geometry.hpp"

namespace retrace::sim {

/// Checks that a robot of radius `robot_radius` (m) can drive the route (polyline in W): the
/// route has at least two points and every point along it (sampled every 2 cm) keeps at least
/// that clearance from the static geometry. Throws core::WorldError naming the first blocked
/// point and route segment ("a route through a building").
void CheckRouteIsDrivable(const StaticGeometry& geometry, const std::vector<Vec2>& route,
                          double robot_radius);

}  // namespace retrace::sim
