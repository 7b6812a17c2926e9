#include "sim/speed_headway.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.hpp"

namespace retrace::sim {

void SpeedHeadwayConfig::Validate() const {
  core::RequireNonNegative("length", length);
  core::RequirePositive("time_gap", time_gap);
}

namespace {

// The centre distance to `o` if it lies ahead of `self` along `direction` in its band, else +inf.
double DistanceInBand(const SocialAgent& self, const Vec2& direction, const SocialAgent& o) {
  const Vec2 d = o.position - self.position;
  if (d.dot(direction) <= 0.0) return std::numeric_limits<double>::infinity();
  const double lateral = std::abs(direction.x() * d.y() - direction.y() * d.x());
  if (lateral >= self.radius + o.radius) return std::numeric_limits<double>::infinity();
  return d.norm();
}

}  // namespace

double Headway(const SocialAgent& self, const Vec2& direction, std::span<const SocialAgent> others,
               const SocialAgent* robot) {
  double best = std::numeric_limits<double>::infinity();
  if (direction.squaredNorm() < 1e-12) return best;
  for (const SocialAgent& o : others) {
    if (o.heading.dot(direction) < 0.0) continue;
    best = std::min(best, DistanceInBand(self, direction, o));
  }
  if (robot != nullptr) best = std::min(best, DistanceInBand(self, direction, *robot));
  return best;
}

double HeadwaySpeed(double headway, double desired_speed, const SpeedHeadwayConfig& config) {
  if (!config.enabled || !std::isfinite(headway)) return desired_speed;
  return std::clamp((headway - config.length) / config.time_gap, 0.0, desired_speed);
}

}  // namespace retrace::sim
