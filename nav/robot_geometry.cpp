#include "nav/robot_geometry.hpp"

#include <cmath>

#include "core/config.hpp"
#include "core/errors.hpp"

namespace retrace::nav {

void RobotGeometry::Validate() const {
  core::RequirePositive("radius", radius);
  if (!std::isfinite(X_RL.x) || !std::isfinite(X_RL.y) || !std::isfinite(X_RL.theta))
    throw core::ConfigError("X_RL", "must be finite [x, y, theta]");
  core::RequireNonNegative("range_min", range_min);
  core::RequirePositive("range_max", range_max);
  core::RequireGreater("range_max", range_max, "range_min", range_min);
}

}  // namespace retrace::nav
