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
  // Points are checked at most kStep apart, and further apart where the clearance proves the
  // stretch in between free: a point with clearance c has clearance >= robot_radius up to
  // c - robot_radius from it. Open space is crossed in steps of up to kLookAhead.
  constexpr double kStep = 0.02;
  constexpr double kLookAhead = 2.0;
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    const Vec2 a = route[i];
    const Vec2 b = route[i + 1];
    const double length = (b - a).norm();
    for (double t = 0.0;;) {
      const Vec2 p = length > 0.0 ? Vec2(a + (b - a) * (t / length)) : a;
      const double clearance = index.Clearance(p, robot_radius + kLookAhead);
      if (clearance >= robot_radius) {
        if (t >= length) break;
        t = std::min(length, t + std::max(kStep, clearance - robot_radius));
        continue;
      }
      {
        std::ostringstream msg;
        msg.precision(3);
        msg << "the route is not drivable: at (" << p.x() << ", " << p.y() << "), on route segment "
            << i << " from point " << i << " to " << i + 1 << ", "
            << (clearance <= 0.0
                    ? "it runs inside an obstacle"
                    : "it passes " + core::FormatNumber(std::round(clearance * 1000) / 1000) +
                          " m from an obstacle")
            << " (the robot needs " << robot_radius << " m)";
        throw core::WorldError(msg.str());
      }
    }
  }
}

}  // namespace retrace::sim
