#include "core/twist.hpp"

#include <cmath>

namespace retrace::core {

Pose2 IntegrateOdometry(const Pose2& X_OR, const OdometryDelta& delta) {
  const double half = 0.5 * delta.dtheta;
  const double chord = delta.distance * Sinc(half);
  const double heading = X_OR.theta + half;
  return {X_OR.x + chord * std::cos(heading), X_OR.y + chord * std::sin(heading),
          X_OR.theta + delta.dtheta};
}

}  // namespace retrace::core
