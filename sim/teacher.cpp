#include "sim/teacher.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/angle.hpp"
#include "core/check.hpp"
#include "core/errors.hpp"
#include "core/limits.hpp"

namespace retrace::sim {
namespace {

constexpr double kMinSegment = 1e-3;  // m
// Heading change (rad) of the route at which a turn counts as fully "sharp" for the speed.
constexpr double kFullSlowTurn = core::kPi / 2.0;
// Vertices turning more than this are driven like a human would: stop at the vertex, turn on
// the spot, go on. Pure pursuit would cut such corners widely, and a reversal leaves it no
// target ahead.
constexpr double kStopTurn = 2.0 * core::kPi / 3.0;
// Speed the teacher keeps when closing in on a stop point, so that it never stalls (m/s).
constexpr double kCreepSpeed = 0.05;
// Gain of the in-place turn toward a target behind the robot (1/s).
constexpr double kTurnGain = 2.0;
// Heading error to the target (rad) below which a turn on the spot ends.
constexpr double kAlignedAngle = 0.2;
// Bound of the wobble in stationary standard deviations.
constexpr double kWobbleBound = 3.0;

}  // namespace

void TeacherConfig::Validate() const {
  core::RequirePositive("speed", speed);
  core::RequirePositive("min_turn_speed", min_turn_speed);
  if (min_turn_speed > speed) {
    throw core::ConfigError("min_turn_speed", "must be <= speed (" + core::FormatNumber(speed) +
                                                  "), got " + core::FormatNumber(min_turn_speed));
  }
  core::RequirePositive("lookahead", lookahead);
  core::RequireNonNegative("turn_lookahead", turn_lookahead);
  core::RequirePositive("max_accel", max_accel);
  core::RequirePositive("max_yaw_rate", max_yaw_rate);
  core::RequireNonNegative("wobble_amplitude", wobble_amplitude);
  if (wobble_amplitude * kWobbleBound > lookahead) {
    throw core::ConfigError("wobble_amplitude", "must be <= lookahead / 3, got " +
                                                    core::FormatNumber(wobble_amplitude));
  }
  core::RequirePositive("wobble_time_constant", wobble_time_constant);
  core::RequirePositive("goal_tolerance", goal_tolerance);
}

void ValidateRoute(const std::vector<core::Vec2>& route) {
  if (route.size() < 2) {
    throw core::ConfigError("route",
                            "needs at least 2 points, got " + std::to_string(route.size()));
  }
  if (static_cast<std::int64_t>(route.size()) > core::kMaxRoutePoints) {
    throw core::ConfigError("route", "has " + std::to_string(route.size()) +
                                         " points; retrace's limit is " +
                                         std::to_string(core::kMaxRoutePoints));
  }
  double length = 0.0;
  for (std::size_t i = 0; i < route.size(); ++i) {
    const std::string key = "route[" + std::to_string(i) + "]";
    core::RequirePoint(key, route[i]);
    if (i == 0) continue;
    const double segment = (route[i] - route[i - 1]).norm();
    if (segment < kMinSegment) {
      throw core::ConfigError(key, "repeats the previous point (segments must be >= 1 mm long)");
    }
    length += segment;
  }
  if (length > core::kMaxRouteLength) {
    throw core::ConfigError(
        "route", "is " + core::FormatNumber(std::round(length)) + " m long; retrace's limit is " +
                     std::to_string(static_cast<long long>(core::kMaxRouteLength)) + " m");
  }
}

Teacher::Teacher(std::vector<core::Vec2> route, const TeacherConfig& config, core::Rng rng)
    : route_(std::move(route)), config_(config), rng_(rng) {
  ValidateRoute(route_);
  config_.Validate();
  arc_.assign(route_.size(), 0.0);
  turn_.assign(route_.size(), 0.0);
  for (std::size_t i = 1; i < route_.size(); ++i) {
    arc_[i] = arc_[i - 1] + (route_[i] - route_[i - 1]).norm();
  }
  for (std::size_t i = 1; i + 1 < route_.size(); ++i) {
    const core::Vec2 a = route_[i] - route_[i - 1];
    const core::Vec2 b = route_[i + 1] - route_[i];
    turn_[i] = std::abs(core::AngleDiff(std::atan2(b.y(), b.x()), std::atan2(a.y(), a.x())));
  }
  next_stop_ = NextStopAfter(0);
}

std::size_t Teacher::NextStopAfter(std::size_t i) const {
  for (std::size_t j = i + 1; j + 1 < route_.size(); ++j) {
    if (turn_[j] > kStopTurn) return j;
  }
  return route_.size() - 1;
}

core::Vec2 Teacher::PointAt(double s, std::size_t* segment) const {
  s = std::clamp(s, 0.0, RouteLength());
  // Last segment whose start is <= s.
  const auto it = std::upper_bound(arc_.begin(), arc_.end(), s);
  std::size_t i = static_cast<std::size_t>(it - arc_.begin());
  i = std::clamp<std::size_t>(i, 1, route_.size() - 1) - 1;
  const double t = (s - arc_[i]) / (arc_[i + 1] - arc_[i]);
  if (segment != nullptr) *segment = i;
  return route_[i] + t * (route_[i + 1] - route_[i]);
}

double Teacher::TurnNear(double s) const {
  const double behind = config_.lookahead;
  const double full = 0.5 * config_.turn_lookahead;
  double sum = 0.0;
  auto it = std::lower_bound(arc_.begin(), arc_.end(), s - behind);
  for (auto i = static_cast<std::size_t>(it - arc_.begin()); i + 1 < route_.size(); ++i) {
    const double ahead = arc_[i] - s;
    if (ahead > config_.turn_lookahead) break;
    sum += ahead <= full ? turn_[i] : turn_[i] * (config_.turn_lookahead - ahead) / full;
  }
  return sum;
}

void Teacher::AdvanceProgress(const core::Vec2& p_WR) {
  progress_.Advance(route_, arc_, p_WR,
                    std::min(progress_.value() + config_.lookahead, arc_[next_stop_]));
  // A stop is reached where the robot stands at it and the progress has come up to it: a route
  // that turns back at a crossing it comes to again later (an out-and-back leg) must not take
  // the later visit for this one.
  if (next_stop_ + 1 < route_.size() &&
      arc_[next_stop_] - progress_.value() <= config_.lookahead &&
      (p_WR - route_[next_stop_]).norm() <= config_.goal_tolerance) {
    progress_.MoveTo(arc_[next_stop_]);
    last_stop_arc_ = progress_.value();
    next_stop_ = NextStopAfter(next_stop_);
  }
}

void Teacher::StepWobble(double dt) {
  // Ornstein–Uhlenbeck, exact discretisation, bounded.
  const double decay = std::exp(-dt / config_.wobble_time_constant);
  const double n = rng_.Normal();
  wobble_ = decay * wobble_ + config_.wobble_amplitude * std::sqrt(1.0 - decay * decay) * n;
  wobble_ = std::clamp(wobble_, -kWobbleBound * config_.wobble_amplitude,
                       kWobbleBound * config_.wobble_amplitude);
}

core::Vec2 Teacher::PursuitTarget(double s_stop) const {
  // The look-ahead shrinks with speed (to half at half the cruising speed): slower in a turn
  // means tighter on the route, as with a human driver.
  const double L = config_.lookahead;
  const double L_pursuit = L * std::clamp(v_ / config_.speed, 0.5, 1.0);
  const double s_target = std::min(progress_.value() + L_pursuit, s_stop);
  std::size_t target_segment = 0;
  const core::Vec2 on_route = PointAt(s_target, &target_segment);
  const core::Vec2 dir = (route_[target_segment + 1] - route_[target_segment]).normalized();
  const double fade =
      std::clamp(std::min(s_stop - s_target, progress_.value() - last_stop_arc_) / L, 0.0, 1.0);
  return on_route + fade * wobble_ * core::Vec2(-dir.y(), dir.x());
}

double Teacher::SpeedLimit(double d_stop, double s_stop, double dt) const {
  const double slow = std::clamp(TurnNear(progress_.value()) / kFullSlowTurn, 0.0, 1.0);
  double v = config_.speed - (config_.speed - config_.min_turn_speed) * slow;
  const double to_stop =
      std::max(d_stop, s_stop - progress_.value()) - 0.5 * config_.goal_tolerance;
  v = std::min(v,
               std::max(kCreepSpeed, std::sqrt(2.0 * config_.max_accel * std::max(0.0, to_stop))));
  return std::min(v, v_ + config_.max_accel * dt);
}

core::Twist Teacher::Command(const core::Pose2& X_WR, double dt) {
  RETRACE_CHECK(dt > 0.0 && std::isfinite(dt));
  if (done_) return {};
  const core::Vec2 p_WR = X_WR.translation();
  const double L = config_.lookahead;
  const double tol = config_.goal_tolerance;

  // Progress, never beyond the next stop point (a sharp vertex or the end): the teacher
  // passes a stop point only by reaching it, then follows the next leg.
  AdvanceProgress(p_WR);
  const double s_stop = arc_[next_stop_];
  const double d_stop = (p_WR - route_[next_stop_]).norm();

  // The end: close to the last point with the progress near the end (a loop route ends where
  // it starts, so closeness alone is not enough).
  if (next_stop_ + 1 == route_.size() && RouteLength() - progress_.value() <= L + tol &&
      d_stop <= tol) {
    done_ = true;
    v_ = 0.0;
    return {};
  }

  StepWobble(dt);
  // Pure-pursuit target, not beyond the next stop point; the wobble fades out near stops.
  const core::Vec2 q = X_WR.Inverse() * PursuitTarget(s_stop);  // target in R
  const double alpha = std::atan2(q.y(), q.x());

  // Target behind (after a stop point, or when pushed off): stop and turn on the spot until
  // facing it.
  if (std::abs(alpha) > core::kPi / 2.0) turning_in_place_ = true;
  if (turning_in_place_ && std::abs(alpha) < kAlignedAngle) turning_in_place_ = false;
  if (turning_in_place_) {
    v_ = 0.0;
    return {0.0, std::clamp(kTurnGain * alpha, -config_.max_yaw_rate, config_.max_yaw_rate)};
  }

  // Speed: cruise, slower for the route's heading changes near the progress point, braking
  // for the next stop point, accelerating at most at max_accel.
  double v = SpeedLimit(d_stop, s_stop, dt);
  const double kappa = q.squaredNorm() > 0.0 ? 2.0 * q.y() / q.squaredNorm() : 0.0;
  double omega = v * kappa;
  if (std::abs(omega) > config_.max_yaw_rate) {
    v = config_.max_yaw_rate / std::abs(kappa);
    omega = std::copysign(config_.max_yaw_rate, kappa);
  }
  v_ = v;
  return {v, omega};
}

}  // namespace retrace::sim
