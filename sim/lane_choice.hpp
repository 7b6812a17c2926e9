#pragma once
// Which lane to walk in, for the `ttc` crowd model: a walker held up by someone slower steps into
// the neighbouring lane that lets it make more progress (the speed-headway rule along each of a
// few directions round the goal's), and a walker meeting someone head-on keeps to its right.
// Pedestrians in counterflow pass each other on a preferred side and so form lanes (Moussaïd,
// Helbing, Garnier, Johansson, Combe & Theraulaz 2009, Proc. R. Soc. B 276, 2755: the
// preference for one side is what turns pairwise avoidance into lanes; Helbing & Molnár 1995).
// Pure functions; vectors in the world frame W.

#include <span>

#include "core/config.hpp"
#include "core/pose2.hpp"
#include "sim/social_force.hpp"
#include "sim/speed_headway.hpp"

namespace retrace::sim {

struct LaneChoiceConfig {
  double max_turn_deg = 30.0;  ///< largest turn away from the goal's direction into another lane
  int turn_steps = 2;          ///< directions tried on each side (0: straight on only)
  /// Largest turn to the right (deg) while someone walking the other way (or the robot) is on a
  /// collision course within keep_right_time; 0: no side preference.
  double keep_right_deg = 35.0;
  double keep_right_time = 5.0;  ///< s of time to collision within which one keeps right
  /// m between the bodies' edges that keeping right leaves when passing (the "collision" it
  /// avoids is with the other's body grown by this much)
  double keep_right_gap = 0.2;
  /// m a walker may walk beside the line of its route (from the last waypoint to the next),
  /// keeping its offset, before it steers back towards the line; 0: it aims at the waypoint.
  double tolerance = 1.0;

  template <class V>
  void Reflect(V& v) {
    v("max_turn_deg", max_turn_deg);
    v("turn_steps", turn_steps);
    v("keep_right_deg", keep_right_deg);
    v("keep_right_time", keep_right_time);
    v("keep_right_gap", keep_right_gap);
    v("tolerance", tolerance);
  }
  /// Throws core::ConfigError naming the key: max_turn_deg and keep_right_deg in [0, 90],
  /// turn_steps in [0, 8], keep_right_time, keep_right_gap and tolerance >= 0.
  void Validate() const;
};

/// The point (W) to walk towards on the way from `segment_start` to `waypoint`: the waypoint
/// moved sideways by the walker's offset from that line, at most config.tolerance either side.
/// The waypoint itself when the tolerance is 0 or the segment shorter than 1 cm.
Vec2 LaneAimPoint(const Vec2& position, const Vec2& segment_start, const Vec2& waypoint,
                  const LaneChoiceConfig& config);

/// True if self's body, walking along `direction` at `speed`, would come within
/// config.keep_right_gap of one of `others` that faces it (its heading against `direction`) and
/// is in front of it, or touch `robot` (may be null; whatever its heading) in front of it, within
/// config.keep_right_time; false when keeping right is off.
bool MeetsSomeoneHeadOn(const SocialAgent& self, const Vec2& direction, double speed,
                        std::span<const SocialAgent> others, const SocialAgent* robot,
                        const LaneChoiceConfig& config);

/// The goal's direction unless MeetsSomeoneHeadOn along it; else turned to the right just as far
/// (in 5° steps, at most keep_right_deg) as clears the way.
Vec2 KeepRight(const SocialAgent& self, const Vec2& goal_direction, double speed,
               std::span<const SocialAgent> others, const SocialAgent* robot,
               const LaneChoiceConfig& config);

/// Where and how fast to walk: a direction (unit, W) and a speed (m/s).
struct WalkingChoice {
  Vec2 direction{0.0, 0.0};
  double speed = 0.0;
};

/// KeepRight's direction; then of it and
/// the directions turned from it by k/turn_steps x max_turn_deg (k = -turn_steps ... turn_steps),
/// the one whose HeadwaySpeed makes the most progress along the goal's direction (speed x
/// cos(turn)), ties to the smaller turn and then to the right; never a turn into someone coming
/// the other way. `robot` (may be null) is kept right of and followed like the others. Straight on
/// at the desired speed when `goal_direction` is zero (then the speed is 0).
WalkingChoice ChooseLane(const SocialAgent& self, const Vec2& goal_direction, double desired_speed,
                         std::span<const SocialAgent> others, const SocialAgent* robot,
                         const LaneChoiceConfig& config, const SpeedHeadwayConfig& headway);

}  // namespace retrace::sim
