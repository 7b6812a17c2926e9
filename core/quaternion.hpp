#pragma once
// The yaw of a 3-D rotation given as a quaternion, as files and messages store headings.

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/angle.hpp"

namespace retrace::core {

/// The yaw (rad, in [-pi, pi)) of the rotation of quaternion (x, y, z, w) (z-y-x Euler angles),
/// which need not be unit: scaled by its largest component first, its squared norm lies in
/// [1, 4], so huge components neither overflow nor turn the yaw into NaN. nullopt for a
/// non-finite component or a norm below 1e-9.
inline std::optional<double> QuaternionYaw(double x, double y, double z, double w) {
  const double m = std::max({std::abs(x), std::abs(y), std::abs(z), std::abs(w)});
  if (!std::isfinite(m) || !std::isfinite(x + y + z + w)) return std::nullopt;
  if (!(m > 0.0)) return std::nullopt;
  const double sx = x / m, sy = y / m, sz = z / m, sw = w / m;
  const double n2 = sx * sx + sy * sy + sz * sz + sw * sw;
  if (!(m * std::sqrt(n2) >= 1e-9)) return std::nullopt;
  // Numerator and denominator both carry the factor 1/n2 of the normalisation; atan2 does not
  // need it.
  return WrapAngle(std::atan2(2.0 * (sw * sz + sx * sy), sw * sw + sx * sx - sy * sy - sz * sz));
}

}  // namespace retrace::core
