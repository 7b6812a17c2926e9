#include "sim/social_force.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/angle.hpp"
#include "core/errors.hpp"

namespace retrace::sim {
namespace {

// Points seen less than this angle apart from the pedestrian belong to the same stretch of
// obstacle; only the nearest of them repels (SelectObstaclePoints).
const double kCosSameObstacle = std::cos(core::DegToRad(45.0));
// Keeps exp() finite for extreme user parameters (tiny ranges).
constexpr double kMaxExponent = 50.0;

}  // namespace

void SocialForceConfig::Validate() const {
  core::RequirePositive("relaxation_time", relaxation_time);
  core::RequireNonNegative("pedestrian_strength", pedestrian_strength);
  core::RequirePositive("pedestrian_range", pedestrian_range);
  core::RequireNonNegative("robot_strength", robot_strength);
  core::RequirePositive("robot_range", robot_range);
  core::RequireNonNegative("obstacle_strength", obstacle_strength);
  core::RequirePositive("obstacle_range", obstacle_range);
  core::RequireNonNegative("step_time", step_time);
  if (!(fov_deg > 0.0 && fov_deg <= 360.0)) {
    throw core::ConfigError("fov_deg", "must be in (0, 360], got " + core::FormatNumber(fov_deg));
  }
  core::RequireInRange("out_of_view_weight", out_of_view_weight, 0.0, 1.0);
  if (!(max_speed_factor >= 1.0) || !std::isfinite(max_speed_factor)) {
    throw core::ConfigError("max_speed_factor",
                            "must be >= 1, got " + core::FormatNumber(max_speed_factor));
  }
  core::RequirePositive("max_acceleration", max_acceleration);
  core::RequirePositive("interaction_range", interaction_range);
  core::RequirePositive("obstacle_cutoff", obstacle_cutoff);
}

Vec2 GoalForce(const Vec2& velocity, const Vec2& direction, double desired_speed,
               const SocialForceConfig& config) {
  return (desired_speed * direction - velocity) / config.relaxation_time;
}

double EllipseSemiMinorAxis(const Vec2& r_ab, const Vec2& step) {
  const double sum = r_ab.norm() + (r_ab - step).norm();
  return 0.5 * std::sqrt(std::max(0.0, sum * sum - step.squaredNorm()));
}

Vec2 AgentRepulsion(const SocialAgent& self, const SocialAgent& other, double strength,
                    double range, const SocialForceConfig& config) {
  const Vec2 r = self.position - other.position;
  const double r_norm = r.norm();
  if (r_norm > config.interaction_range || r_norm < 1e-9) return Vec2::Zero();
  const Vec2 s = (other.velocity - self.velocity) * config.step_time;
  const Vec2 r_minus_s = r - s;
  const double rs_norm = r_minus_s.norm();
  const double b = EllipseSemiMinorAxis(r, s);
  // grad_r b = (|r| + |r - s|) / (4 b) * (r/|r| + (r - s)/|r - s|); with s = 0 it is r/|r|.
  Vec2 grad = r / r_norm;
  if (rs_norm > 1e-9 && b > 1e-9) {
    grad = (r_norm + rs_norm) / (4.0 * b) * (r / r_norm + r_minus_s / rs_norm);
  }
  const double gap = b - self.radius - other.radius;
  const double magnitude = strength / range * std::exp(std::min(-gap / range, kMaxExponent));
  const Vec2 f = magnitude * grad;
  return f.allFinite() ? f : Vec2::Zero();
}

Vec2 ObstacleRepulsion(const Vec2& position, const Vec2& closest_point,
                       const SocialForceConfig& config) {
  const Vec2 d = position - closest_point;
  const double dist = d.norm();
  if (dist > config.obstacle_cutoff || dist < 1e-9) return Vec2::Zero();
  const double magnitude = config.obstacle_strength / config.obstacle_range *
                           std::exp(std::min(-dist / config.obstacle_range, kMaxExponent));
  return magnitude * (d / dist);
}

double FieldOfViewWeight(const Vec2& direction, const Vec2& force,
                         const SocialForceConfig& config) {
  const double f_norm = force.norm();
  const double e_norm = direction.norm();
  if (f_norm <= 0.0 || e_norm <= 0.0) return 1.0;
  const double cos_half_fov = std::cos(core::DegToRad(0.5 * config.fov_deg));
  return direction.dot(-force) >= f_norm * e_norm * cos_half_fov ? 1.0 : config.out_of_view_weight;
}

void SelectObstaclePoints(const Vec2& position, std::vector<Vec2>* points) {
  std::vector<Vec2>& pts = *points;
  std::stable_sort(pts.begin(), pts.end(), [&](const Vec2& a, const Vec2& b) {
    return (a - position).squaredNorm() < (b - position).squaredNorm();
  });
  std::size_t kept = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec2 d = pts[i] - position;
    const double n = d.norm();
    bool keep = true;
    for (std::size_t k = 0; k < kept && keep; ++k) {
      const Vec2 dk = pts[k] - position;
      const double nk = dk.norm();
      if ((pts[k] - pts[i]).squaredNorm() < 1e-18)
        keep = false;  // shared vertex
      else if (n > 0.0 && nk > 0.0 && d.dot(dk) >= kCosSameObstacle * n * nk)
        keep = false;
    }
    if (keep) pts[kept++] = pts[i];
  }
  pts.resize(kept);
}

Vec2 RobotForce(const SocialForceInputs& in, const SocialForceConfig& config) {
  if (in.robot == nullptr) return Vec2::Zero();
  const Vec2 f =
      AgentRepulsion(in.self, *in.robot, config.robot_strength, config.robot_range, config);
  return FieldOfViewWeight(in.direction, f, config) * f;
}

Vec2 ObstacleForce(const SocialForceInputs& in, const SocialForceConfig& config) {
  // Walls act whatever the walking direction (no field-of-view weight): people do not back
  // into walls either.
  Vec2 obstacles = Vec2::Zero();
  for (const Vec2& q : in.obstacle_points)
    obstacles += ObstacleRepulsion(in.self.position, q, config);
  if (in.walking_line_clear) {
    const double braking = obstacles.dot(in.direction);
    if (braking < 0.0) obstacles -= braking * in.direction;
  }
  return obstacles;
}

Vec2 CapAcceleration(const Vec2& a, double max_acceleration) {
  const double n = a.norm();
  return n > max_acceleration ? Vec2(a * (max_acceleration / n)) : a;
}

Vec2 SocialForce(const SocialForceInputs& in, const SocialForceConfig& config) {
  Vec2 total = GoalForce(in.self.velocity, in.direction, in.desired_speed, config);
  for (const SocialAgent& other : in.others) {
    const Vec2 f =
        AgentRepulsion(in.self, other, config.pedestrian_strength, config.pedestrian_range, config);
    total += FieldOfViewWeight(in.direction, f, config) * f;
  }
  if (in.robot != nullptr) total += RobotForce(in, config);
  total += ObstacleForce(in, config);
  return CapAcceleration(total, config.max_acceleration);
}

Vec2 IntegrateVelocity(const Vec2& velocity, const Vec2& acceleration, double dt,
                       double max_speed) {
  Vec2 v = velocity + acceleration * dt;
  const double n = v.norm();
  if (n > max_speed) v *= max_speed / n;
  return v;
}

}  // namespace retrace::sim
