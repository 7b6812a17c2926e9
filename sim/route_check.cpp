#include "sim/route_check.hpp"

#include <cmath>
#include <sstream>

#include "core/config.hpp"
#include "core/errors.hpp"
#include "sim/geometry_index.hpp"

namespace retrace::sim {

void CheckRouteIsDrivable(const StaticGeometry& geometry, const std::vector<Vec2>& route,
                          double robot_radius) {
  if (route.size() < 2) throw core::WorldError("the route needs at least 2 points");
  const GeometryIndex index(geometry, 1.0);
  constexpr double kStep = 0.02;
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    const Vec2 a = route[i];
    const Vec2 b = route[i + 1];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / kStep)));
    for (int k = 0; k <= n; ++k) {
      const Vec2 p = a + (b - a) * (static_cast<double>(k) / n);
      const double clearance = index.Clearance(p, robot_radius);
      if (clearance < robot_radius) {
        std::ostringstream msg;
        msg.precision(3);
        msg << "the route is not drivable: at (" << p.x() << ", " << p.y() << "), on route segment "
            << i << " from point " << i << " to " << i + 1 << ", "
            << (clearance <= 0.0 ? "it runs inside an obstacle"
                                 : "it passes " + core::FormatNumber(std::round(clearance * 1000) / 1000) +
                                       " m from an obstacle")
            << " (the robot needs " << robot_radius << " m)";
        throw core::WorldError(msg.str());
      }
    }
  }
}

}  // namespace retrace::sim
