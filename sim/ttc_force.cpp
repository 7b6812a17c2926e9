#include "sim/ttc_force.hpp"

#include <cmath>
#include <limits>

#include "core/errors.hpp"

namespace retrace::sim {

void TtcForceConfig::Validate() const {
  core::RequireNonNegative("strength", strength);
  core::RequirePositive("time_horizon", time_horizon);
  core::RequirePositive("relaxation_time", relaxation_time);
  core::RequirePositive("range", range);
  core::RequirePositive("max_pair_acceleration", max_pair_acceleration);
}

double DiscTimeToCollision(const Vec2& x, const Vec2& v, double r) {
  const double c = x.squaredNorm() - r * r;
  if (c <= 0.0) return 0.0;
  const double a = v.squaredNorm();
  const double b = -x.dot(v);  // > 0: closing
  if (!(a > 0.0) || b <= 0.0) return std::numeric_limits<double>::infinity();
  const double d = b * b - a * c;
  if (d <= 0.0) return std::numeric_limits<double>::infinity();  // passes by
  // The smaller root (b - sqrt(d)) / a, written as c / (b + sqrt(d)) to keep its digits.
  return c / (b + std::sqrt(d));
}

double TtcEnergy(double tau, const TtcForceConfig& config) {
  if (!std::isfinite(tau)) return 0.0;
  return config.strength / (tau * tau) * std::exp(-tau / config.time_horizon);
}

Vec2 TtcRepulsion(const SocialAgent& self, const SocialAgent& other, const TtcForceConfig& config) {
  const Vec2 x = self.position - other.position;
  const double dist = x.norm();
  if (dist > config.range || dist < 1e-9) return Vec2::Zero();
  double r = self.radius + other.radius;
  // Overlapping by delta = r - dist: the overlap's depth stands in for the radius sum.
  if (dist <= r) r = r - dist;
  const Vec2 v = self.velocity - other.velocity;
  const double a = v.squaredNorm();
  const double b = -x.dot(v);
  const double c = x.squaredNorm() - r * r;
  const double d = b * b - a * c;
  if (!(a > 1e-12) || b <= 0.0 || c <= 0.0 || d <= 0.0) return Vec2::Zero();
  const double sqrt_d = std::sqrt(d);
  const double tau = c / (b + sqrt_d);
  if (!(tau > 0.0)) return Vec2::Zero();
  // -grad_x E = -k exp(-tau/tau0) / (|v|² tau²) (2/tau + 1/tau0) (v - (|v|² x - (x.v) v) / sqrt(d))
  const double scale = -config.strength * std::exp(-tau / config.time_horizon) / (a * tau * tau) *
                       (2.0 / tau + 1.0 / config.time_horizon);
  Vec2 f = scale * (v - (a * x + b * v) / sqrt_d);
  if (!f.allFinite()) return Vec2::Zero();
  return CapAcceleration(f, config.max_pair_acceleration);
}

Vec2 TtcDrivingForce(const Vec2& velocity, const Vec2& preferred, const TtcForceConfig& config) {
  return (preferred - velocity) / config.relaxation_time;
}

Vec2 TtcForce(const SocialForceInputs& in, const Vec2& preferred, const TtcForceConfig& config,
              const SocialForceConfig& social) {
  Vec2 total = TtcDrivingForce(in.self.velocity, preferred, config);
  for (const SocialAgent& other : in.others) {
    Vec2 f = TtcRepulsion(in.self, other, config);
    // Someone coming the other way (an obtuse crossing angle) is avoided by a change of path,
    // not of speed: the force loses its part along the walking direction.
    if (other.heading.dot(in.direction) < 0.0) f -= f.dot(in.direction) * in.direction;
    total += f;
  }
  total += RobotForce(in, social);
  total += ObstacleForce(in, social);
  return CapAcceleration(total, social.max_acceleration);
}

}  // namespace retrace::sim
