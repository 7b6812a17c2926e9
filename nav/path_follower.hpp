#pragma once
// The path follower (paper §4.3, docs/DESIGN.md §5): PD control on the lateral and heading errors
// to a taught path with a curvature feed-forward, a speed profile that looks ahead for curves and
// the end of the path, and monotonic progress.
//
// Control law (every Compute, errors at the projection s* of the robot onto the path):
//   e_y   = signed lateral offset of the robot from the path (m, > 0: robot left of the path)
//   e_psi = reference heading - robot heading (rad, > 0: the robot must turn left), the
//           reference being the path tangent at s*: the direction of the chord over
//           tangent_window centred on s*, so that keyframe wobble does not make it jump
//   kappa = path curvature at s* (change of that tangent over tangent_window, 1/m)
//   omega = v * kappa + kp_heading * e_psi + kd_heading * d(e_psi)/dt
//                     - kp_lateral * e_y' - kd_lateral * d(e_y')/dt
// where e_y' is e_y clipped to +-lateral_error_clip (so that a robot far off the path
// approaches it at a bounded angle instead of circling) and d/dt is a finite difference over
// the control period dt, low-pass filtered with time constant derivative_filter_tau.
// Speed: the minimum of max_speed * max(0, cos e_psi); over the look-ahead window
// [s*, s* + look_ahead], min(sqrt(max_lateral_accel / kappa), 0.8 * max_yaw_rate / kappa)
// braked back to s* at decel; and sqrt(2 * decel * path length left); then floored at
// min_speed while the goal is not reached. Never negative. Past the end of the path (the
// robot overshot it sideways) the reference is the bearing to the last pose.
//
// The paper steered towards a target point 2 m ahead. Steering at a look-ahead point (or with
// the feed-forward curvature averaged over a window ahead) cuts corners: on 2 m radius S-curves
// it left 0.19 m (1 m ahead) to 0.36 m (2 m ahead) of error where the local law above leaves
// under 0.03 m. The look-ahead is kept where it helps: the speed profile's preview.

#include <cstddef>
#include <limits>

#include "core/config.hpp"
#include "core/path.hpp"
#include "core/path_projection.hpp"
#include "core/pose2.hpp"
#include "core/twist.hpp"

namespace retrace::nav {

/// Gains and limits of the path follower. Defaults suit a 1 m/s differential-drive robot on
/// taught indoor/outdoor paths (keyframes every 0.5 m): at 1 m/s the lateral loop has a
/// natural frequency of about 1 rad/s and a damping ratio of about 0.85.
struct PathFollowerConfig {
  /// m. How far ahead of the projection the path is scanned for curvature to slow down in
  /// time (at least the braking distance max_speed^2 / (2 decel) is scanned). The paper's
  /// look-ahead of 2 m: two seconds at full speed.
  double look_ahead = 2.0;
  /// m. Progress is searched only in [s_prev, s_prev + progress_window] of arc length, so it
  /// never jumps to a later part of a path that passes nearby.
  double progress_window = 1.5;
  /// m. The progress moves only while the robot is within this distance of the path: a robot
  /// off the route (a wide detour, a lost estimate, a recorded drive that went elsewhere or
  /// drove the route backwards) does not drag it along to the end of the path and its map
  /// switch. It waits where the robot left the path.
  double progress_max_distance = 2.0;
  /// m. While off the path, the robot may rejoin it this far ahead of the progress (it cut a
  /// corner or took a parallel corridor): the progress moves there once it is within
  /// progress_max_distance of it.
  double rejoin_window = 10.0;
  /// m. Length of the chord that defines the path tangent (and curvature) at an arc length.
  double tangent_window = 0.5;
  double max_speed = 1.0;     ///< m/s
  double min_speed = 0.05;    ///< m/s, floor while driving so that the robot never stalls
  /// m/s. The speed limit while the localizer is lost, and until a re-acquisition has held for
  /// augmented.confirm_updates updates (nav::Navigator): the robot creeps on, so that scans keep
  /// coming, but never drives on at speed from an estimate that just jumped.
  double creep_speed = 0.2;
  double max_yaw_rate = 1.0;  ///< rad/s, |omega| limit of the command
  double kp_lateral = 1.0;    ///< rad/s per m of lateral error
  double kd_lateral = 0.5;    ///< rad/s per m/s of lateral error rate
  double kp_heading = 1.2;    ///< rad/s per rad of heading error
  double kd_heading = 0.05;   ///< rad/s per rad/s of heading error rate (keep < 1)
  /// s. Time constant of the first-order low-pass on both error derivatives (0 = none).
  double derivative_filter_tau = 0.1;
  /// m. The lateral error is clipped to +-this before the PD terms.
  double lateral_error_clip = 1.0;
  double max_lateral_accel = 0.5;  ///< m/s², v <= sqrt(max_lateral_accel / curvature)
  double decel = 0.5;              ///< m/s², braking for curves ahead and for the goal
  /// m. The goal is reached when the robot is within this distance of the last path pose and
  /// the rest of the path is shorter than this control step's travel (v * dt): the robot
  /// stops at the end of the path, not this far before it.
  double goal_tolerance = 0.1;

  template <class V>
  void Reflect(V& v) {
    v("look_ahead", look_ahead);
    v("progress_window", progress_window);
    v("progress_max_distance", progress_max_distance);
    v("rejoin_window", rejoin_window);
    v("tangent_window", tangent_window);
    v("max_speed", max_speed);
    v("min_speed", min_speed);
    v("creep_speed", creep_speed);
    v("max_yaw_rate", max_yaw_rate);
    v("kp_lateral", kp_lateral);
    v("kd_lateral", kd_lateral);
    v("kp_heading", kp_heading);
    v("kd_heading", kd_heading);
    v("derivative_filter_tau", derivative_filter_tau);
    v("lateral_error_clip", lateral_error_clip);
    v("max_lateral_accel", max_lateral_accel);
    v("decel", decel);
    v("goal_tolerance", goal_tolerance);
  }
  /// Throws core::ConfigError naming the key: lengths, speeds, accelerations, max_yaw_rate and
  /// goal_tolerance must be > 0 (min_speed >= 0 and <= max_speed), gains and
  /// derivative_filter_tau >= 0, kd_heading < 1.
  void Validate() const;
};

/// One follower step's command and diagnostics.
struct FollowerOutput {
  core::Twist command;         ///< (v, omega) in R; v >= 0; zero once the goal is reached
  std::size_t index = 0;       ///< progress: index of the last path pose reached (arc <= s*)
  double remaining = 0.0;      ///< m, path length left from the projection to the end
  double lateral_error = 0.0;  ///< m, > 0 when the robot is left of the path
  double heading_error = 0.0;  ///< rad, path heading minus robot heading, in [-pi, pi)
  bool goal_reached = false;
  /// The robot was farther than progress_max_distance from the path ahead of its progress
  /// (and rejoin_window did not find it either): the progress waited.
  bool off_path = false;
};

/// A path's end counts as reached within this much arc length of it (m).
inline constexpr double kPathEndTolerance = 0.05;

/// The follower is at the end of its path: its goal reached, or on the path within
/// kPathEndTolerance of the end. The map server's rule for a path's end (eq. 1) and any stack
/// that replays the taught paths share it.
inline bool AtPathEnd(const FollowerOutput& f) {
  return f.goal_reached || (f.remaining <= kPathEndTolerance && !f.off_path);
}

/// Follows a path given in the current map frame M from the localizer's pose estimates.
class PathFollower {
 public:
  /// Throws core::ConfigError if the config is invalid.
  explicit PathFollower(const PathFollowerConfig& config);

  const PathFollowerConfig& config() const { return config_; }

  /// Starts following `path` (poses in the current map frame M) from its first pose: progress
  /// and derivative state are reset. An empty path counts as already reached.
  void SetPath(const core::Path& path);
  /// As SetPath, but the progress starts at arc length s (m, clamped to the path): where the
  /// robot entered the path (the map server hands a path over by place).
  void SetPathAt(const core::Path& path, double s);
  const core::Path& path() const { return path_; }

  /// One control step from the estimate X_MR (robot R in map M) after dt s (the control
  /// period, > 0). Progress only moves forward. Once the goal is reached it stays reached
  /// (until the next SetPath) and the command is zero.
  FollowerOutput Compute(const core::Pose2& X_MR, double dt);

 private:
  double TangentAt(double s) const;
  double CurvatureAt(double s) const;
  double SpeedLimitAhead(double s) const;
  std::size_t IndexAt(double s) const;
  bool AdvanceProgress(const core::Vec2& p_M, double length);
  // The errors at arc length s (the control law's e_y, e_psi, kappa).
  struct TrackingErrors {
    double lateral = 0.0;          // m
    double lateral_clipped = 0.0;  // m, to +-lateral_error_clip
    double heading = 0.0;          // rad
    double curvature = 0.0;        // 1/m, 0 past the end
    bool past_end = false;         // the reference is the bearing to the last pose
  };
  TrackingErrors ErrorsAt(const core::Pose2& X_MR, double s, double remaining) const;
  void FilterRates(const TrackingErrors& e, double dt);
  double Speed(const TrackingErrors& e, double s, double remaining, double distance_to_end) const;

  PathFollowerConfig config_;
  core::Path path_;
  core::ForwardProgress progress_;  // s* of the last step (m)
  bool goal_reached_ = false;
  bool have_previous_ = false;
  double previous_lateral_ = 0.0;
  double previous_heading_ = 0.0;
  double lateral_rate_ = 0.0;  // filtered d(e_y')/dt (m/s)
  double heading_rate_ = 0.0;  // filtered d(e_psi)/dt (rad/s)
};

}  // namespace retrace::nav
