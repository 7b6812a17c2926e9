#include "nav/path_follower.hpp"

#include <algorithm>
#include <cmath>

#include "core/angle.hpp"
#include "core/check.hpp"

namespace retrace::nav {
namespace {

constexpr double kTinyLength = 1e-9;          // m, below this a path or chord has no direction
constexpr double kCurvatureSampleStep = 0.1;  // m, spacing of the curvature preview samples
// Share of max_yaw_rate the curvature feed-forward may use; the rest is left to the PD terms.
constexpr double kFeedForwardYawShare = 0.8;

const PathFollowerConfig& Validated(const PathFollowerConfig& config) {
  config.Validate();
  return config;
}

}  // namespace

void PathFollowerConfig::Validate() const {
  core::RequirePositive("look_ahead", look_ahead);
  core::RequirePositive("progress_window", progress_window);
  core::RequirePositive("progress_max_distance", progress_max_distance);
  if (!(rejoin_window >= progress_window)) {
    throw core::ConfigError("rejoin_window", "must be >= progress_window (" +
                                                 core::FormatNumber(progress_window) + "), got " +
                                                 core::FormatNumber(rejoin_window));
  }
  core::RequirePositive("tangent_window", tangent_window);
  core::RequirePositive("max_speed", max_speed);
  core::RequireInRange("min_speed", min_speed, 0.0, max_speed);
  core::RequireInRange("creep_speed", creep_speed, 0.0, max_speed);
  core::RequirePositive("max_yaw_rate", max_yaw_rate);
  core::RequireNonNegative("kp_lateral", kp_lateral);
  core::RequireNonNegative("kd_lateral", kd_lateral);
  core::RequireNonNegative("kp_heading", kp_heading);
  // The heading rate contains the robot's own yaw rate: a gain >= 1 on it makes the discrete
  // loop oscillate from one control step to the next.
  if (!(kd_heading >= 0.0 && kd_heading < 1.0)) {
    throw core::ConfigError("kd_heading",
                            "must be in [0, 1), got " + core::FormatNumber(kd_heading));
  }
  core::RequireNonNegative("derivative_filter_tau", derivative_filter_tau);
  core::RequirePositive("lateral_error_clip", lateral_error_clip);
  core::RequirePositive("max_lateral_accel", max_lateral_accel);
  core::RequirePositive("decel", decel);
  core::RequirePositive("goal_tolerance", goal_tolerance);
}

PathFollower::PathFollower(const PathFollowerConfig& config) : config_(Validated(config)) {}

void PathFollower::SetPath(const core::Path& path) {
  path_ = path;
  progress_ = {};
  goal_reached_ = path_.empty();
  have_previous_ = false;
  previous_lateral_ = 0.0;
  previous_heading_ = 0.0;
  lateral_rate_ = 0.0;
  heading_rate_ = 0.0;
}

void PathFollower::SetPathAt(const core::Path& path, double s) {
  SetPath(path);
  const double length = path_.Length();
  if (length <= kTinyLength) return;
  progress_.MoveTo(std::clamp(s, 0.0, length));
}

double PathFollower::TangentAt(double s) const {
  const double h = 0.5 * config_.tangent_window;
  const core::Pose2 a = path_.AtArcLength(s - h);
  const core::Pose2 b = path_.AtArcLength(s + h);
  if (core::Distance(a, b) < kTinyLength) return path_.AtArcLength(s).theta;
  return std::atan2(b.y - a.y, b.x - a.x);
}

double PathFollower::CurvatureAt(double s) const {
  const double h = 0.5 * config_.tangent_window;
  const double s1 = std::max(0.0, s - h);
  const double s2 = std::min(path_.Length(), s + h);
  if (s2 - s1 < kTinyLength) return 0.0;
  return core::AngleDiff(TangentAt(s2), TangentAt(s1)) / (s2 - s1);
}

double PathFollower::SpeedLimitAhead(double s) const {
  // v(s') <= min(sqrt(a_lat / kappa), share * max_yaw_rate / kappa) at every s' ahead, braked
  // back to s at decel: v(s) <= sqrt(v(s')^2 + 2 * decel * (s' - s)).
  const double preview =
      std::max(config_.look_ahead, config_.max_speed * config_.max_speed / (2.0 * config_.decel));
  const double end = std::min(path_.Length(), s + preview);
  double limit = config_.max_speed;
  for (double sp = s;; sp += kCurvatureSampleStep) {
    const double here = std::min(sp, end);
    const double kappa = std::abs(CurvatureAt(here));
    if (kappa > kTinyLength) {
      const double v_curve = std::min(std::sqrt(config_.max_lateral_accel / kappa),
                                      kFeedForwardYawShare * config_.max_yaw_rate / kappa);
      limit = std::min(limit, std::sqrt(v_curve * v_curve + 2.0 * config_.decel * (here - s)));
    }
    if (here >= end) break;
  }
  return limit;
}

std::size_t PathFollower::IndexAt(double s) const {
  // Largest i with ArcLength(i) <= s (0 if none).
  std::size_t lo = 0;
  std::size_t hi = path_.size();
  while (hi - lo > 1) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (path_.ArcLength(mid) <= s) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

bool PathFollower::AdvanceProgress(const core::Vec2& p_M, double length) {
  // Monotonic progress inside the search window, starting from the first path pose; off the
  // path it waits, unless the robot has rejoined the path a little further ahead.
  const double s = progress_.value();
  core::PathProjection near = core::ProjectOntoPath(path_.positions(), path_.arc_lengths(), p_M,
                                                    s, std::min(length, s + config_.progress_window));
  if (near.distance > config_.progress_max_distance) {
    near = core::ProjectOntoPath(path_.positions(), path_.arc_lengths(), p_M, s,
                                 std::min(length, s + config_.rejoin_window));
    if (near.distance > config_.progress_max_distance) return false;
  }
  progress_.MoveTo(near.s);
  return true;
}

PathFollower::TrackingErrors PathFollower::ErrorsAt(const core::Pose2& X_MR, double s,
                                                   double remaining) const {
  // Beyond the end of the path (or on a path without length) the reference is the bearing to
  // the last pose, with no lateral term.
  const double length = path_.Length();
  const core::Vec2 p_M = X_MR.translation();
  const core::Vec2 end_M = path_.back().translation();
  const core::Pose2 ref = path_.AtArcLength(s);
  double reference_heading = length > kTinyLength ? TangentAt(s) : ref.theta;
  const core::Vec2 d = p_M - ref.translation();
  const double c = std::cos(reference_heading);
  const double sn = std::sin(reference_heading);
  TrackingErrors e;
  e.lateral = -sn * d.x() + c * d.y();
  const double along = c * d.x() + sn * d.y();
  e.past_end = remaining <= kTinyLength && (along > 0.0 || length <= kTinyLength);
  if (e.past_end) {
    reference_heading = std::atan2(end_M.y() - p_M.y(), end_M.x() - p_M.x());
    e.lateral = 0.0;
  } else {
    e.curvature = CurvatureAt(s);
  }
  e.heading = core::AngleDiff(reference_heading, X_MR.theta);
  e.lateral_clipped =
      std::clamp(e.lateral, -config_.lateral_error_clip, config_.lateral_error_clip);
  return e;
}

void PathFollower::FilterRates(const TrackingErrors& e, double dt) {
  // Real derivatives: finite differences over the control period, low-pass filtered.
  if (have_previous_) {
    const double alpha = dt / (config_.derivative_filter_tau + dt);
    const double lateral_raw = (e.lateral_clipped - previous_lateral_) / dt;
    const double heading_raw = core::AngleDiff(e.heading, previous_heading_) / dt;
    lateral_rate_ += alpha * (lateral_raw - lateral_rate_);
    heading_rate_ += alpha * (heading_raw - heading_rate_);
  }
  have_previous_ = true;
  previous_lateral_ = e.lateral_clipped;
  previous_heading_ = e.heading;
}

double PathFollower::Speed(const TrackingErrors& e, double s, double remaining,
                           double distance_to_end) const {
  // Heading error, curvature ahead, stop at the end of the path; floor; never < 0.
  double v = config_.max_speed * std::max(0.0, std::cos(e.heading));
  if (!e.past_end) v = std::min(v, SpeedLimitAhead(s));
  v = std::min(v, std::sqrt(2.0 * config_.decel * (e.past_end ? distance_to_end : remaining)));
  return std::clamp(v, config_.min_speed, config_.max_speed);
}

FollowerOutput PathFollower::Compute(const core::Pose2& X_MR, double dt) {
  RETRACE_CHECK(std::isfinite(dt) && dt > 0.0);
  RETRACE_CHECK(std::isfinite(X_MR.x) && std::isfinite(X_MR.y) && std::isfinite(X_MR.theta));
  FollowerOutput out;
  if (path_.empty()) {
    out.goal_reached = true;
    return out;
  }
  const double length = path_.Length();
  const core::Vec2 p_M = X_MR.translation();
  if (length > kTinyLength && !goal_reached_) out.off_path = !AdvanceProgress(p_M, length);
  const double s = progress_.value();
  const double remaining = std::max(0.0, length - s);
  const double distance_to_end = (p_M - path_.back().translation()).norm();
  out.index = IndexAt(s);
  out.remaining = remaining;
  if (goal_reached_) {
    out.index = path_.size() - 1;
    out.goal_reached = true;
    return out;
  }

  const TrackingErrors e = ErrorsAt(X_MR, s, remaining);
  FilterRates(e, dt);
  const double v = Speed(e, s, remaining, distance_to_end);
  out.lateral_error = e.lateral;
  out.heading_error = e.heading;
  // The goal: close to the last pose, and the rest of the path is covered within this step.
  if (distance_to_end <= config_.goal_tolerance && remaining <= v * dt) {
    goal_reached_ = true;
    out.index = path_.size() - 1;
    out.goal_reached = true;
    return out;
  }
  double omega = v * e.curvature + config_.kp_heading * e.heading +
                 config_.kd_heading * heading_rate_ - config_.kp_lateral * e.lateral_clipped -
                 config_.kd_lateral * lateral_rate_;
  omega = std::clamp(omega, -config_.max_yaw_rate, config_.max_yaw_rate);
  out.command = {v, omega};
  RETRACE_CHECK(out.command.v >= 0.0 && std::isfinite(out.command.omega));
  return out;
}

}  // namespace retrace::nav
