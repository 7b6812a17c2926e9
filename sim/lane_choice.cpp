#include "sim/lane_choice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "sim/ttc_force.hpp"

namespace retrace::sim {
namespace {

// Steps (rad) in which a walker turns to the right until nobody comes at it.
const double kKeepRightStep = core::DegToRad(5.0);

// `v` turned by `angle` (rad, counter-clockwise).
Vec2 Turned(const Vec2& v, double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

}  // namespace

void LaneChoiceConfig::Validate() const {
  core::RequireInRange("max_turn_deg", max_turn_deg, 0.0, 90.0);
  core::RequireIntInRange("turn_steps", turn_steps, 0, 8);
  core::RequireInRange("keep_right_deg", keep_right_deg, 0.0, 90.0);
  core::RequireNonNegative("keep_right_time", keep_right_time);
  core::RequireNonNegative("keep_right_gap", keep_right_gap);
  core::RequireNonNegative("tolerance", tolerance);
}

Vec2 LaneAimPoint(const Vec2& position, const Vec2& segment_start, const Vec2& waypoint,
                  const LaneChoiceConfig& config) {
  const Vec2 line = waypoint - segment_start;
  const double length = line.norm();
  if (config.tolerance <= 0.0 || length < 0.01) return waypoint;
  const Vec2 normal(-line.y() / length, line.x() / length);
  const double offset =
      std::clamp((position - segment_start).dot(normal), -config.tolerance, config.tolerance);
  return waypoint + offset * normal;
}

bool MeetsSomeoneHeadOn(const SocialAgent& self, const Vec2& direction, double speed,
                        std::span<const SocialAgent> others, const SocialAgent* robot,
                        const LaneChoiceConfig& config) {
  if (config.keep_right_deg <= 0.0 || config.keep_right_time <= 0.0) return false;
  const Vec2 v = speed * direction;
  auto collides = [&](const SocialAgent& o, double gap) {
    const Vec2 x = self.position - o.position;
    if (x.dot(direction) >= 0.0) return false;  // behind
    return DiscTimeToCollision(x, v - o.velocity, self.radius + o.radius + gap) <
           config.keep_right_time;
  };
  // The berth given to the robot is the robot term's (social_force.robot_*): just clear it.
  if (robot != nullptr && collides(*robot, 0.0)) return true;
  for (const SocialAgent& o : others) {
    // Someone walking the other way, passed keep_right_gap clear.
    if (o.heading.dot(direction) < 0.0 && collides(o, config.keep_right_gap)) return true;
  }
  return false;
}

Vec2 KeepRight(const SocialAgent& self, const Vec2& goal_direction, double speed,
               std::span<const SocialAgent> others, const SocialAgent* robot,
               const LaneChoiceConfig& config) {
  if (!MeetsSomeoneHeadOn(self, goal_direction, speed, others, robot, config)) {
    return goal_direction;
  }
  // Just as far to the right as clears the way, in steps of kKeepRightStep.
  const double max_turn = core::DegToRad(config.keep_right_deg);
  Vec2 d = goal_direction;
  for (double turn = kKeepRightStep; turn < max_turn + 1e-9; turn += kKeepRightStep) {
    d = Turned(goal_direction, -std::min(turn, max_turn));
    if (!MeetsSomeoneHeadOn(self, d, speed, others, robot, config)) return d;
  }
  return Turned(goal_direction, -max_turn);
}

WalkingChoice ChooseLane(const SocialAgent& self, const Vec2& goal_direction, double desired_speed,
                         std::span<const SocialAgent> others, const SocialAgent* robot,
                         const LaneChoiceConfig& config, const SpeedHeadwayConfig& headway) {
  if (goal_direction.squaredNorm() < 1e-12) return {goal_direction, 0.0};
  const Vec2 ahead = KeepRight(self, goal_direction, desired_speed, others, robot, config);
  WalkingChoice best{ahead,
                     HeadwaySpeed(Headway(self, ahead, others, robot), desired_speed, headway)};
  double best_progress = best.speed * ahead.dot(goal_direction);
  const double step = core::DegToRad(config.max_turn_deg) / std::max(1, config.turn_steps);
  for (int k = 1; k <= config.turn_steps && best.speed < desired_speed; ++k) {
    for (const double turn : {-k * step, k * step}) {  // right first: people keep right
      const Vec2 d = Turned(ahead, turn);
      const double speed = HeadwaySpeed(Headway(self, d, others, robot), desired_speed, headway);
      const double progress = speed * d.dot(goal_direction);
      // Nobody overtakes into someone coming the other way.
      if (progress > best_progress + 1e-9 &&
          !MeetsSomeoneHeadOn(self, d, desired_speed, others, robot, config)) {
        best = {d, speed};
        best_progress = progress;
      }
    }
  }
  return best;
}

}  // namespace retrace::sim
