#pragma once
// The teacher: the simulated human operator who drives the route during teaching (docs/DESIGN.md
// §4).

#include <cstddef>
#include <vector>

#include "core/config.hpp"
#include "core/path_projection.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "core/twist.hpp"

namespace retrace::sim {

/// How the teacher drives: pure pursuit on the route at a cruising speed, slower in turns, with
/// a small, slowly varying lateral offset like a human driver's.
struct TeacherConfig {
  double speed = 0.8;           ///< cruising speed on straights (m/s)
  double min_turn_speed = 0.3;  ///< speed at a right-angle turn (m/s)
  /// Pure-pursuit look-ahead along the route at cruising speed (m); it shrinks with the speed,
  /// down to half of it at half the cruising speed and below.
  double lookahead = 1.0;
  /// How far ahead along the route (m) turns slow the teacher down. The speed falls linearly
  /// from `speed` to `min_turn_speed` as the summed absolute heading change of the route's
  /// vertices near the progress point grows from 0 to 90°; vertices from `lookahead` behind to
  /// turn_lookahead / 2 ahead count fully, farther ones fade out up to turn_lookahead.
  double turn_lookahead = 2.0;
  double max_accel = 0.5;             ///< limit on speeding up, and braking before stops (m/s²)
  double max_yaw_rate = 1.0;          ///< rad/s; the speed drops to keep within it
  double wobble_amplitude = 0.05;     ///< stationary std of the lateral offset (m); 0 disables
  double wobble_time_constant = 3.0;  ///< correlation time of the lateral offset (s)
  double goal_tolerance = 0.2;        ///< the route is done within this distance of its end (m)

  template <class V>
  void Reflect(V& v) {
    v("speed", speed);
    v("min_turn_speed", min_turn_speed);
    v("lookahead", lookahead);
    v("turn_lookahead", turn_lookahead);
    v("max_accel", max_accel);
    v("max_yaw_rate", max_yaw_rate);
    v("wobble_amplitude", wobble_amplitude);
    v("wobble_time_constant", wobble_time_constant);
    v("goal_tolerance", goal_tolerance);
  }
  /// Throws core::ConfigError naming the offending key.
  void Validate() const;
};

/// Checks that a route (polyline in W, m) has at least two points, finite coordinates and no
/// zero-length segment (consecutive points closer than 1 mm). Throws core::ConfigError with the
/// key path "route" or "route[i]".
void ValidateRoute(const std::vector<core::Vec2>& route);

/// Drives a route from its first to its last point, in order, from ground-truth poses.
///
/// Progress along the route is tracked monotonically: each command moves it to the route point
/// closest to the robot within `lookahead` ahead of the current progress (never behind it), so
/// a route that crosses or revisits itself (loops, hairpins, several laps, out and back) is
/// followed in order and never short-cut to a later, nearby part. Steering is pure pursuit
/// toward the route point a look-ahead further on, shifted sideways by the wobble: an
/// Ornstein–Uhlenbeck offset (stationary std `wobble_amplitude`, time constant
/// `wobble_time_constant`, clamped to ±3 std, faded out near stops). Vertices where the route
/// turns by more than 120° are stop points, as for a human driver: the teacher brakes, reaches
/// the vertex within `goal_tolerance`, turns on the spot and goes on; the progress cannot pass
/// a stop point otherwise. When the target is behind the robot it also turns on the spot.
class Teacher {
 public:
  /// Throws core::ConfigError if the route or the config is invalid.
  Teacher(std::vector<core::Vec2> route, const TeacherConfig& config, core::Rng rng);

  /// The command (v in m/s, omega in rad/s) for the next control period of dt seconds (> 0),
  /// given the ground-truth pose X_WR. Zero once Done().
  core::Twist Command(const core::Pose2& X_WR, double dt);

  /// True once the robot came within goal_tolerance of the last point with the progress at the
  /// end of the route; stays true.
  bool Done() const { return done_; }
  /// Arc length of the route (m).
  double RouteLength() const { return arc_.back(); }
  /// Arc length along the route reached so far (m), non-decreasing.
  double Progress() const { return progress_.value(); }
  /// The current lateral wobble offset (m, positive to the left of the route).
  double wobble() const { return wobble_; }

  const std::vector<core::Vec2>& route() const { return route_; }

 private:
  /// Index of the first sharp vertex after point i, or of the last point.
  std::size_t NextStopAfter(std::size_t i) const;
  /// Point of the route at arc length s (clamped), with its segment index.
  core::Vec2 PointAt(double s, std::size_t* segment) const;
  /// Absolute heading change of the route near arc length s (rad): the vertices from
  /// lookahead behind to turn_lookahead / 2 ahead count fully, then fade out linearly up to
  /// turn_lookahead ahead.
  double TurnNear(double s) const;
  /// Advances the progress to the robot at p_WR (W), never beyond the next stop point; passes
  /// that point (on to the next leg) once the robot is within goal_tolerance of it.
  void AdvanceProgress(const core::Vec2& p_WR);
  /// Steps the lateral wobble over dt (s).
  void StepWobble(double dt);
  /// The pure-pursuit target (W): the route point a speed-dependent look-ahead past the
  /// progress, not beyond the stop point at arc length s_stop (m), offset by the wobble.
  core::Vec2 PursuitTarget(double s_stop) const;
  /// The speed (m/s) for the next dt (s): cruise, slower near turns, braking for the stop point
  /// d_stop (m) away at arc length s_stop (m), accelerating at most at max_accel.
  double SpeedLimit(double d_stop, double s_stop, double dt) const;

  std::vector<core::Vec2> route_;
  std::vector<double> arc_;   ///< arc length at each point (m)
  std::vector<double> turn_;  ///< absolute heading change at each point (rad; 0 at the ends)
  TeacherConfig config_;
  core::Rng rng_;
  std::size_t next_stop_ = 0;       ///< next point where the teacher stops (sharp vertex or end)
  double last_stop_arc_ = 0.0;      ///< arc length of the last stop point passed (m)
  core::ForwardProgress progress_;  ///< along the route, never beyond the next stop
  double wobble_ = 0.0;
  double v_ = 0.0;  ///< last commanded speed (m/s)
  bool turning_in_place_ = false;
  bool done_ = false;
};

}  // namespace retrace::sim
