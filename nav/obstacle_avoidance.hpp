#pragma once
// Reactive obstacle avoidance (docs/DESIGN.md §5): predicts the robot's circular footprint along
// the commanded arc against the current scan and, if it would collide, picks the closest
// collision-free (v, omega) from a sampled window; stops when nothing is free.
//
// Selection when the desired command (v_d, omega_d) collides within the prediction distance:
// candidates are omega_d + k * omega_step for |k| <= omega_window / omega_step (within
// +-max_yaw_rate) and v = v_d * f for f in speed_factors. Their cost is |omega - omega_d|
// (stay as close as possible to the follower's intent), plus side_switch_penalty for a
// candidate on the other side of omega_d than the current detour (hysteresis: without it the
// follower's pull back to the path makes the choice flip sides every step and the robot ends
// up stuck in front of the obstacle). Ties go to the preferred speed (factors in the given
// order), then to the larger clearance, then to the left.
//
// The window is the whole yaw-rate range by default. The paper's +-0.4 rad/s around omega_d
// cannot hold a detour against a follower that pulls back to the path: once beside the
// obstacle the follower asks for about +-1 rad/s and every candidate in the window turns
// back into it.
//
// The safety margin is a preference, the bare footprint the constraint: when no candidate
// keeps the margin, candidates that only keep the footprint clear are taken before stopping.
// Otherwise a robot that has come within a little more than the margin of an obstacle beside
// it (a bin it is passing) finds every forward arc "blocked" and stops there for good.

#include <limits>
#include <vector>

#include "core/config.hpp"
#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "core/twist.hpp"
#include "nav/robot_geometry.hpp"

namespace retrace::nav {

/// Prediction and search window of the avoidance (the footprint is the robot's: RobotGeometry).
/// Defaults match the simulated robot's default speed (1 m/s), the paper's omega step
/// (0.02 rad/s) and its speed x 0.8 while avoiding; the window spans the whole yaw-rate range
/// (see above).
struct ObstacleAvoidanceConfig {
  bool enabled = true;         ///< false: Filter passes the command through unchanged
  double safety_margin = 0.1;  ///< m, added to the robot's radius for points not already that close
  /// s. The footprint is predicted over v_d * horizon of arc length (at least
  /// min_prediction_distance) for every candidate, so slowing down never shortens the look.
  /// The paper used 5 s; at 1 m/s, 2 s (2 m, four braking distances at 1 m/s²) reacts in time
  /// without swerving for walls that the taught path turns away from a few metres ahead (the
  /// prediction holds omega constant) or stopping 5 m before a standing pedestrian.
  double horizon = 2.0;
  double min_prediction_distance = 0.5;  ///< m
  /// A candidate must be free over candidate_reach times the prediction distance (in
  /// [1, 10]), so that it clears the obstacle rather than reaching it just beyond the
  /// prediction; if none is, candidates free over the prediction distance are taken before
  /// stopping.
  double candidate_reach = 2.0;
  double omega_window = 2.0;  ///< rad/s, half-width of the candidate window around omega_d
  double omega_step = 0.02;   ///< rad/s
  double max_yaw_rate = 1.0;  ///< rad/s, candidates beyond it are not considered
  /// rad/s, cost added to candidates that reverse the side of the current detour.
  double side_switch_penalty = 1.0;
  /// Speed candidates as fractions of the desired speed, most preferred first (each in
  /// (0, 1]); the paper slows to 0.8 while avoiding.
  std::vector<double> speed_factors = {0.8, 0.5};
  /// m, the emergency-stop zone: the rectangle 0 < x <= radius + emergency_stop_length,
  /// |y| <= emergency_stop_width / 2 in R. Points behind or beside it never count. Shorter than
  /// safety_margin so that the avoidance's own detours do not run into it: it catches what
  /// appears suddenly (a pedestrian stepping in).
  double emergency_stop_length = 0.05;
  double emergency_stop_width = 0.6;  ///< m

  template <class V>
  void Reflect(V& v) {
    v("enabled", enabled);
    v("safety_margin", safety_margin);
    v("horizon", horizon);
    v("min_prediction_distance", min_prediction_distance);
    v("candidate_reach", candidate_reach);
    v("omega_window", omega_window);
    v("omega_step", omega_step);
    v("max_yaw_rate", max_yaw_rate);
    v("side_switch_penalty", side_switch_penalty);
    v("speed_factors", speed_factors);
    v("emergency_stop_length", emergency_stop_length);
    v("emergency_stop_width", emergency_stop_width);
  }
  /// Throws core::ConfigError naming the key: horizon, omega_step, max_yaw_rate and
  /// emergency_stop_width must be > 0, the other lengths, omega_window and
  /// side_switch_penalty >= 0, candidate_reach in [1, 10],
  /// omega_window / omega_step <= 1000, speed_factors non-empty with each in (0, 1].
  void Validate() const;
};

/// The filtered command and what happened.
struct AvoidanceOutput {
  core::Twist command;    ///< (v, omega) in R to send to the robot
  bool modified = false;  ///< the command differs from the desired one
  bool blocked = false;   ///< no candidate is free: stopped, waiting for a clear path
  /// A point lies in the zone ahead: v = 0, the yaw rate is kept (clamped to max_yaw_rate).
  bool emergency_stop = false;
  /// s, time until the desired command's footprint first touches a point (+inf if not within
  /// the prediction distance; 0 if a point is already in its way).
  double time_to_collision = std::numeric_limits<double>::infinity();
};

/// Arc length (m) the centre of a disc of radius `radius` (m) travels from the origin of R
/// along the arc of curvature `curvature` (1/m, > 0 turning left; 0 straight along +x) before
/// the disc first contains `p_R` (a point in R), or +inf if that does not happen within
/// `max_distance` (m). A point already inside the disc counts at 0 if the motion approaches it
/// (p_R.x > 0) and is otherwise ignored until the disc would enter it again.
double DistanceToContact(double curvature, double radius, double max_distance,
                         const core::Vec2& p_R);

/// Filters the follower's command against the latest scan.
class ObstacleAvoidance {
 public:
  /// Avoidance for the robot `robot` (its radius is the footprint; scans come from its LiDAR at
  /// X_RL). Throws core::ConfigError if the config or the geometry is invalid.
  ObstacleAvoidance(const ObstacleAvoidanceConfig& config, const RobotGeometry& robot);

  const ObstacleAvoidanceConfig& config() const { return config_; }
  const RobotGeometry& robot() const { return robot_; }

  /// Returns a collision-free version of `desired` ((v, omega) in R) for `scan` (taken by the
  /// LiDAR L mounted at X_RL). Commands with v <= 0 are passed through (a circular footprint
  /// turning in place sweeps nothing). Valid readings and -inf readings (closer than
  /// range_min: taken as an obstacle at range_min) are obstacles; +inf and NaN are not.
  AvoidanceOutput Filter(const core::Twist& desired, const core::LaserScan& scan);

 private:
  struct Clearance {
    double contact = std::numeric_limits<double>::infinity();    // m of arc to first contact
    double clearance = std::numeric_limits<double>::infinity();  // m, only if requested
  };
  /// `margin`: keep safety_margin from points farther than it (false: the bare footprint).
  Clearance Evaluate(double v, double omega, double distance, bool want_clearance,
                     bool margin = true);
  // A free arc: its command, the index of its speed factor and its cost (rad/s, +inf: none).
  struct Candidate {
    core::Twist command;
    std::size_t factor = 0;
    double cost = std::numeric_limits<double>::infinity();
  };
  // Fills points_R_ with the scan's obstacle points in R.
  void CollectPoints(const core::LaserScan& scan);
  // Whether a point lies in the emergency-stop rectangle ahead of the robot's centre line.
  bool InEmergencyZone() const;
  // On side 0 (left: omega >= omega_d) or 1 (right), the candidate closest to desired.omega
  // whose arc is free over `reach` (m), at its first free speed factor; cost +inf if none.
  Candidate FirstFreeOnSide(const core::Twist& desired, int side, double reach, bool margin);
  // Of two candidates of which at least one is free, the side to take: the lower cost, then
  // the preferred speed factor, then the larger clearance, then the left (0).
  int PickSide(const Candidate (&best)[2], double reach, bool margin);

  ObstacleAvoidanceConfig config_;
  RobotGeometry robot_;
  std::vector<core::Vec2> points_R_;  // scan points of the current Filter call, in R
  int last_side_ = 0;                 // side of the current detour: +1 left, -1 right, 0 none
  std::size_t hint_ = 0;              // index of the last blocking point, tested first
  bool exact_contact_ = false;        // Evaluate must find the first contact, not just any
  // cos and sin of the beam angles of the last scan's geometry (angle_min, angle_increment,
  // beam count), which rarely changes: CollectPoints computes them once.
  double table_angle_min_ = 0.0, table_angle_increment_ = 0.0;
  std::vector<double> beam_cos_, beam_sin_;
};

}  // namespace retrace::nav
