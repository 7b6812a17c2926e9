#pragma once
// The social-force model of pedestrian motion (Helbing & Molnár 1995) as pure functions.
// "Forces" are accelerations (m/s², force per unit mass); all vectors are in the world frame W.
//
//   dv/dt = (v0 e - v) / tau                      goal attraction (relaxation)
//         + sum_b w(e, -f_ab) f_ab                 other pedestrians (elliptic potential)
//         + w(e, -f_aR) f_aR                       the robot (same potential, its own strength)
//         + sum_B f_aB                             static obstacles (exponential potential)
//
// Deviations from the 1995 paper: the ellipse is stretched along the *relative* velocity
// (Johansson, Helbing & Shukla 2007, "elliptical specification II"), so that people anticipate
// a collision course with a standing robot too; the potential is evaluated on the gap between
// the bodies' surfaces (b minus the sum of radii) rather than between point pedestrians; when
// the straight line to the waypoint is known to be clear, obstacles steer but do not brake
// (with U0 = 10 m²/s², R = 0.2 m the two jambs of a 1 m door push back harder than the goal
// pulls, and people would stop in front of every door); and the total acceleration is capped.

#include <span>
#include <vector>

#include "core/config.hpp"
#include "core/pose2.hpp"

namespace retrace::sim {

using core::Vec2;

/// Social-force parameters. Defaults: the values of Helbing & Molnár as used by pedsim,
/// lightsfm and PySocialForce (tau 0.5 s, sigma 0.3 m, U0 10 m²/s², R 0.2 m, elliptic step
/// 2 s, field of view 200° with weight 0.5 behind, v_max = 1.3 v0) except the pedestrian
/// strength V0: 0.5 m²/s² instead of 2.1, so that the crowd's speed-density relation follows
/// Weidmann's (1993) curve within 15 % from free walking to 2 persons/m² (`retrace
/// crowd-check`, docs/CROWD.md "Crowd check"). 2.1 belongs to the 1995 ellipse built on the
/// other person's velocity; on the relative velocity and the gap between bodies used here it
/// made people walking towards each other brake from 5 m away, and a two-way corridor jammed
/// at 2 persons/m². Plus a robot repulsion stronger and with a longer range than a
/// pedestrian's: people give a machine a wider berth than each other, and without it they
/// ignore the robot.
struct SocialForceConfig {
  double relaxation_time = 0.5;      ///< tau (s)
  double pedestrian_strength = 0.5;  ///< V0 (m²/s²); Helbing & Molnár: 2.1 (see above)
  double pedestrian_range = 0.3;     ///< sigma (m)
  double robot_strength = 8.0;       ///< V0 for the robot (m²/s²)
  double robot_range = 0.5;          ///< sigma for the robot (m)
  double obstacle_strength = 10.0;   ///< U0 (m²/s²)
  double obstacle_range = 0.2;       ///< R (m)
  double step_time = 2.0;            ///< Delta t of the elliptic potential (s)
  double fov_deg = 200.0;            ///< full field of view 2 phi (deg)
  double out_of_view_weight = 0.5;   ///< c: weight of interactions outside the field of view
  double max_speed_factor = 1.3;     ///< speed cap as a multiple of the desired speed
  double max_acceleration = 8.0;     ///< cap on the total acceleration (m/s²)
  double interaction_range = 5.0;    ///< pedestrians/robot farther than this (m) are ignored
  double obstacle_cutoff = 1.5;      ///< obstacle points farther than this (m) are ignored

  template <class V>
  void Reflect(V& v) {
    v("relaxation_time", relaxation_time);
    v("pedestrian_strength", pedestrian_strength);
    v("pedestrian_range", pedestrian_range);
    v("robot_strength", robot_strength);
    v("robot_range", robot_range);
    v("obstacle_strength", obstacle_strength);
    v("obstacle_range", obstacle_range);
    v("step_time", step_time);
    v("fov_deg", fov_deg);
    v("out_of_view_weight", out_of_view_weight);
    v("max_speed_factor", max_speed_factor);
    v("max_acceleration", max_acceleration);
    v("interaction_range", interaction_range);
    v("obstacle_cutoff", obstacle_cutoff);
  }
  /// Throws core::ConfigError naming the key: times, ranges and caps > 0, strengths >= 0,
  /// fov_deg in (0, 360], out_of_view_weight in [0, 1], max_speed_factor >= 1.
  void Validate() const;
};

/// A disc-shaped agent at one instant: position (W, m), velocity (W, m/s), radius (m), and the
/// way it faces (unit vector in W towards where it means to walk; zero: nowhere, it stands).
struct SocialAgent {
  Vec2 position{0.0, 0.0};
  Vec2 velocity{0.0, 0.0};
  double radius = 0.3;
  Vec2 heading{0.0, 0.0};
};

/// Goal attraction (v0 e - v) / tau: relaxes `velocity` (m/s) to `desired_speed` (m/s) along
/// the unit vector `direction` with time constant tau.
Vec2 GoalForce(const Vec2& velocity, const Vec2& direction, double desired_speed,
               const SocialForceConfig& config);

/// Semi-minor axis b (m) of the elliptic potential for relative position r_ab = r_a - r_b (m)
/// and relative step s = (v_b - v_a) * step_time (m): 2b = sqrt((|r| + |r - s|)^2 - |s|^2).
double EllipseSemiMinorAxis(const Vec2& r_ab, const Vec2& step);

/// Repulsion on `self` from `other` (pedestrian or robot) with strength V0 (m²/s²) and range
/// sigma (m): -grad_r V0 exp(-(b - r_self - r_other) / sigma) with b from EllipseSemiMinorAxis,
/// without the field-of-view weight. Zero beyond config.interaction_range.
Vec2 AgentRepulsion(const SocialAgent& self, const SocialAgent& other, double strength,
                    double range, const SocialForceConfig& config);

/// Repulsion of a pedestrian at `position` from the obstacle point `closest_point` (W, m):
/// U0/R exp(-d/R) along the direction away from the point, d the centre distance.
/// Zero beyond config.obstacle_cutoff.
Vec2 ObstacleRepulsion(const Vec2& position, const Vec2& closest_point,
                       const SocialForceConfig& config);

/// Field-of-view weight w(e, -f): 1 if the source of force f (at -f from the pedestrian) lies
/// within fov_deg/2 of the walking direction e, out_of_view_weight otherwise.
double FieldOfViewWeight(const Vec2& direction, const Vec2& force, const SocialForceConfig& config);

/// Keeps only the obstacle points that matter: drops duplicates (shared polygon vertices) and
/// points hidden behind a nearer point in nearly the same direction (the far face of a thin
/// wall, staircase edges of imported maps): of points less than 45° apart as seen from
/// `position`, only the nearest is kept. The result is sorted by distance.
/// Works in place on `points`.
void SelectObstaclePoints(const Vec2& position, std::vector<Vec2>* points);

/// Everything a pedestrian reacts to in one step.
struct SocialForceInputs {
  SocialAgent self;
  Vec2 direction{1.0, 0.0};  ///< unit vector towards the current waypoint (zero: stand)
  double desired_speed = 1.34;
  std::span<const SocialAgent> others;    ///< other pedestrians (not self)
  const SocialAgent* robot = nullptr;     ///< the robot, if any
  std::span<const Vec2> obstacle_points;  ///< obstacle points, e.g. from SelectObstaclePoints
  /// The straight line to the waypoint is clear of static geometry (walk planner): obstacle
  /// repulsion then loses its component against `direction`.
  bool walking_line_clear = false;
};

/// The robot's repulsion on in.self (m/s²), weighted by the field of view; zero without a robot.
Vec2 RobotForce(const SocialForceInputs& in, const SocialForceConfig& config);

/// The walls' repulsion on in.self (m/s²): the sum over in.obstacle_points, without its component
/// against in.direction when in.walking_line_clear.
Vec2 ObstacleForce(const SocialForceInputs& in, const SocialForceConfig& config);

/// `a` scaled down to at most `max_acceleration` (m/s²) in norm.
Vec2 CapAcceleration(const Vec2& a, double max_acceleration);

/// Total acceleration (m/s²) on a pedestrian, capped at config.max_acceleration.
Vec2 SocialForce(const SocialForceInputs& in, const SocialForceConfig& config);

/// Explicit Euler step of the velocity: v + a dt, capped at max_speed (m/s).
Vec2 IntegrateVelocity(const Vec2& velocity, const Vec2& acceleration, double dt, double max_speed);

}  // namespace retrace::sim
