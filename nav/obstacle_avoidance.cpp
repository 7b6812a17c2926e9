#include "nav/obstacle_avoidance.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/angle.hpp"
#include "core/check.hpp"

namespace retrace::nav {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kStraight = 1e-9;  // 1/m, below this |curvature| the arc is a straight line
constexpr double kTwoPi = 2.0 * core::kPi;

template <class T>
const T& Validated(const T& value) {
  value.Validate();
  return value;
}

// Position of the footprint centre after travelling `sigma` rad along the arc of signed
// curvature kappa (|kappa| > kStraight) from the origin of R, heading +x.
core::Vec2 ArcPoint(double kappa, double sigma) {
  const double rho = 1.0 / std::abs(kappa);
  const double sgn = kappa > 0.0 ? 1.0 : -1.0;
  return {rho * std::sin(sigma), sgn * rho * (1.0 - std::cos(sigma))};
}

// Travelled angle in [0, 2*pi) at which the centre of the arc's circle looks towards p.
double TravelAngle(double kappa, const core::Vec2& q) {
  // q = p - c. The start point seen from the centre is u = (0, -sgn); the motion goes
  // counter-clockwise for kappa > 0 and clockwise otherwise.
  const double sgn = kappa > 0.0 ? 1.0 : -1.0;
  double sigma = sgn * std::atan2(sgn * q.x(), -sgn * q.y());
  if (sigma < 0.0) sigma += kTwoPi;
  return sigma;
}

// Distance (m) from p to the curve traced by the footprint centre over `distance` m of arc.
double DistanceToTrace(double kappa, double distance, const core::Vec2& p) {
  if (std::abs(kappa) < kStraight) {
    return (p - core::Vec2(std::clamp(p.x(), 0.0, distance), 0.0)).norm();
  }
  const double rho = 1.0 / std::abs(kappa);
  const core::Vec2 c(0.0, 1.0 / kappa);
  const core::Vec2 q = p - c;
  const double sweep = std::min(distance / rho, kTwoPi);
  if (TravelAngle(kappa, q) <= sweep) return std::abs(q.norm() - rho);
  return std::min(p.norm(), (p - ArcPoint(kappa, sweep)).norm());
}

}  // namespace

void ObstacleAvoidanceConfig::Validate() const {
  core::RequireNonNegative("safety_margin", safety_margin);
  core::RequirePositive("horizon", horizon);
  core::RequireNonNegative("min_prediction_distance", min_prediction_distance);
  core::RequireNonNegative("omega_window", omega_window);
  core::RequirePositive("omega_step", omega_step);
  if (omega_window / omega_step > 1000.0) {
    throw core::ConfigError("omega_step",
                            "gives more than 1000 candidates per side (omega_window " +
                                core::FormatNumber(omega_window) + ")");
  }
  core::RequirePositive("max_yaw_rate", max_yaw_rate);
  core::RequireNonNegative("side_switch_penalty", side_switch_penalty);
  core::RequireInRange("candidate_reach", candidate_reach, 1.0, 10.0);
  if (speed_factors.empty()) throw core::ConfigError("speed_factors", "must not be empty");
  for (std::size_t i = 0; i < speed_factors.size(); ++i) {
    const double f = speed_factors[i];
    if (!(f > 0.0 && f <= 1.0)) {
      throw core::ConfigError("speed_factors[" + std::to_string(i) + "]",
                              "must be in (0, 1], got " + core::FormatNumber(f));
    }
  }
  core::RequireNonNegative("emergency_stop_length", emergency_stop_length);
  core::RequirePositive("emergency_stop_width", emergency_stop_width);
}

double DistanceToContact(double curvature, double radius, double max_distance,
                         const core::Vec2& p_R) {
  const double r2 = radius * radius;
  const bool inside = p_R.squaredNorm() < r2;
  if (inside && p_R.x() > 0.0) return 0.0;  // already touching and moving towards it
  if (std::abs(curvature) < kStraight) {
    const double py2 = p_R.y() * p_R.y();
    if (py2 >= r2) return kInf;
    const double entry = p_R.x() - std::sqrt(r2 - py2);
    // Inside but moving away: a straight line never comes back.
    if (inside || entry < 0.0) return kInf;
    return entry <= max_distance ? entry : kInf;
  }
  // The centre runs on a circle of radius rho around c; the disc contains p while the
  // centre's angle is within beta of p's: |c + rho*u(phi) - p|^2 < r^2
  // <=> cos(phi - phi_p) > (d^2 + rho^2 - r^2) / (2 d rho).
  const double rho = 1.0 / std::abs(curvature);
  const core::Vec2 q = p_R - core::Vec2(0.0, 1.0 / curvature);
  const double d = q.norm();
  if (std::abs(d - rho) >= radius) return kInf;
  if (d < kStraight) return kInf;  // p at the centre: inside all along, moving away from it
  const double cos_beta = (d * d + rho * rho - r2) / (2.0 * d * rho);
  if (cos_beta <= -1.0) return kInf;  // inside all along the circle, and not approached
  const double beta = std::acos(std::min(cos_beta, 1.0));
  double entry = TravelAngle(curvature, q) - beta;
  if (entry < 0.0) entry += kTwoPi;  // inside now: the next entry is after a full turn
  const double s = entry * rho;
  return s <= max_distance ? s : kInf;
}

ObstacleAvoidance::ObstacleAvoidance(const ObstacleAvoidanceConfig& config,
                                     const RobotGeometry& robot)
    : config_(Validated(config)), robot_(Validated(robot)) {}

ObstacleAvoidance::Clearance ObstacleAvoidance::Evaluate(double v, double omega, double distance,
                                                         bool want_clearance, bool margin) {
  RETRACE_CHECK(v > 0.0);
  const double kappa = omega / v;
  const double inflated = robot_.radius + (margin ? config_.safety_margin : 0.0);
  const double inflated2 = inflated * inflated;
  Clearance out;
  const std::size_t n = points_R_.size();
  // Start at the point that blocked the previous candidate: neighbouring arcs are usually
  // blocked by the same point, so a blocked candidate is rejected after one test.
  const std::size_t first = hint_ < n ? hint_ : 0;
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t i = first + j < n ? first + j : first + j - n;
    const core::Vec2& p = points_R_[i];
    // A point already within the margin only has to stay outside the bare footprint, so the
    // robot can still move away from (or along) something that came too close.
    const double radius = p.squaredNorm() < inflated2 ? robot_.radius : inflated;
    if (want_clearance) {
      out.clearance = std::min(out.clearance, DistanceToTrace(kappa, distance, p) - radius);
    }
    if (p.norm() > distance + radius) continue;
    const double s = DistanceToContact(kappa, radius, distance, p);
    if (s < out.contact) {
      out.contact = s;
      if (!want_clearance) {
        hint_ = i;
        // Only whether the arc is free matters past the desired command's evaluation.
        if (s == 0.0 || !exact_contact_) break;
      }
    }
  }
  return out;
}

void ObstacleAvoidance::CollectPoints(const core::LaserScan& scan) {
  // A -inf reading means something closer than range_min.
  points_R_.clear();
  points_R_.reserve(scan.size());
  if (beam_cos_.size() != scan.size() || table_angle_min_ != scan.angle_min ||
      table_angle_increment_ != scan.angle_increment) {
    table_angle_min_ = scan.angle_min;
    table_angle_increment_ = scan.angle_increment;
    beam_cos_.resize(scan.size());
    beam_sin_.resize(scan.size());
    for (std::size_t i = 0; i < scan.size(); ++i) {
      beam_cos_[i] = std::cos(scan.Angle(i));
      beam_sin_[i] = std::sin(scan.Angle(i));
    }
  }
  const core::PoseTransform X_RL(robot_.X_RL);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const float reading = scan.ranges[i];
    double range = 0.0;
    if (std::isinf(reading) && reading < 0.0f) {
      range = scan.range_min;
    } else if (scan.Valid(i)) {
      range = reading;
    } else {
      continue;
    }
    points_R_.push_back(X_RL(core::Vec2(range * beam_cos_[i], range * beam_sin_[i])));
  }
}

bool ObstacleAvoidance::InEmergencyZone() const {
  const double zone_x = robot_.radius + config_.emergency_stop_length;
  const double zone_y = 0.5 * config_.emergency_stop_width;
  for (const core::Vec2& p : points_R_) {
    if (p.x() > 0.0 && p.x() <= zone_x && std::abs(p.y()) <= zone_y) return true;
  }
  return false;
}

ObstacleAvoidance::Candidate ObstacleAvoidance::FirstFreeOnSide(const core::Twist& desired,
                                                                int side, double reach,
                                                                bool margin) {
  const int steps = static_cast<int>(std::floor(config_.omega_window / config_.omega_step + 1e-9));
  const std::size_t no_factor = config_.speed_factors.size();
  const int sign = side == 0 ? 1 : -1;
  for (int k = side == 0 ? 0 : 1; k <= steps; ++k) {
    const double omega = desired.omega + sign * k * config_.omega_step;
    if (std::abs(omega) > config_.max_yaw_rate + 1e-12) break;
    for (std::size_t f = 0; f < no_factor; ++f) {
      const double v = desired.v * config_.speed_factors[f];
      if (std::isfinite(Evaluate(v, omega, reach, false, margin).contact)) continue;
      const bool switches = k > 0 && last_side_ != 0 && last_side_ != sign;
      return {
          {v, omega}, f, k * config_.omega_step + (switches ? config_.side_switch_penalty : 0.0)};
    }
  }
  return {};
}

int ObstacleAvoidance::PickSide(const Candidate (&best)[2], double reach, bool margin) {
  if (best[0].cost != best[1].cost) return best[1].cost < best[0].cost ? 1 : 0;
  if (best[0].factor != best[1].factor) return best[1].factor < best[0].factor ? 1 : 0;
  const double left =
      Evaluate(best[0].command.v, best[0].command.omega, reach, true, margin).clearance;
  const double right =
      Evaluate(best[1].command.v, best[1].command.omega, reach, true, margin).clearance;
  return right > left ? 1 : 0;
}

AvoidanceOutput ObstacleAvoidance::Filter(const core::Twist& desired, const core::LaserScan& scan) {
  RETRACE_CHECK(std::isfinite(desired.v) && std::isfinite(desired.omega));
  AvoidanceOutput out;
  out.command = desired;
  if (!config_.enabled || !(desired.v > 0.0)) return out;
  CollectPoints(scan);

  const double distance = std::max(desired.v * config_.horizon, config_.min_prediction_distance);
  exact_contact_ = true;  // the first contact of the desired command: time_to_collision
  const double contact = Evaluate(desired.v, desired.omega, distance, false).contact;
  exact_contact_ = false;
  out.time_to_collision = contact / desired.v;

  if (InEmergencyZone()) {
    // Turning in place sweeps nothing with a circular footprint: keeping the yaw rate lets the
    // follower turn away instead of deadlocking in front of a static obstacle.
    out.emergency_stop = true;
    out.command = {0.0, std::clamp(desired.omega, -config_.max_yaw_rate, config_.max_yaw_rate)};
    out.modified = true;
    return out;
  }
  if (!std::isfinite(contact)) {
    last_side_ = 0;  // the detour is over
    return out;
  }

  // Per side, the free candidate closest to omega_d (its first free speed factor); then the
  // side with the lower cost |omega - omega_d| (+ side_switch_penalty when it reverses the
  // previous detour), then the preferred speed, then the larger clearance, then the left.
  // Candidates must stay free over candidate_reach times the prediction distance: otherwise
  // the closest free arc is one that merely meets the obstacle just beyond the prediction,
  // and the robot creeps towards it until no arc is free any more. Where nothing is free that
  // far (tight spaces), the prediction distance itself is the fallback, then the same without
  // the safety margin (only the footprint must stay clear), before giving up.
  struct Tier {
    double reach;
    bool margin;
  };
  for (const Tier tier : {Tier{config_.candidate_reach * distance, true}, Tier{distance, true},
                          Tier{distance, false}}) {
    const Candidate best[2] = {FirstFreeOnSide(desired, 0, tier.reach, tier.margin),
                               FirstFreeOnSide(desired, 1, tier.reach, tier.margin)};
    if (!std::isfinite(best[0].cost) && !std::isfinite(best[1].cost)) continue;
    const int pick = PickSide(best, tier.reach, tier.margin);
    const double turn = best[pick].command.omega - desired.omega;
    if (turn != 0.0) last_side_ = turn > 0.0 ? 1 : -1;
    out.command = best[pick].command;
    out.modified = true;
    return out;
  }
  out.command = {};
  out.modified = true;
  out.blocked = true;
  return out;
}

}  // namespace retrace::nav
