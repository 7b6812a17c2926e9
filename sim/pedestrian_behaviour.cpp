#include "sim/pedestrian_behaviour.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace retrace::sim {
namespace {

// A walker coming to a target slows so as to stop there within this time (s).
constexpr double kArrivalTime = 0.8;

// Unit vector from the robot's centre towards `position` (the robot's heading when on it).
Vec2 AwayFromRobot(const Vec2& position, const RobotDisc& robot) {
  const Vec2 d = position - robot.center;
  const double n = d.norm();
  return n > 1e-9 ? Vec2(d / n) : Vec2(-robot.heading);
}

}  // namespace

void RobotBehaviourConfig::Validate() const {
  core::RequirePositive("notice_distance", notice_distance);
  core::RequireNonNegative("surprised_time", surprised_time);
  core::RequireNonNegative("curious_time", curious_time);
  core::RequireNonNegative("curious_gap", curious_gap);
  core::RequireNonNegative("scared_strength", scared_strength);
  core::RequirePositive("scared_range", scared_range);
  core::RequireNonNegative("threatening_time", threatening_time);
  core::RequireNonNegative("threatening_gap", threatening_gap);
  core::RequireNonNegative("rest_time", rest_time);
}

bool Reacts(RobotBehaviour behaviour) {
  return behaviour != RobotBehaviour::kRegular && behaviour != RobotBehaviour::kImpassive;
}

double ReactionTime(RobotBehaviour behaviour, const RobotBehaviourConfig& config) {
  switch (behaviour) {
    case RobotBehaviour::kSurprised:
      return config.surprised_time;
    case RobotBehaviour::kCurious:
      return config.curious_time;
    case RobotBehaviour::kThreatening:
      return config.threatening_time;
    default:
      return 0.0;
  }
}

ReactionTarget ReactionGoal(RobotBehaviour behaviour, const Vec2& position, double radius,
                            double desired_speed, const RobotDisc& robot,
                            const RobotBehaviourConfig& config) {
  const Vec2 away = AwayFromRobot(position, robot);
  Vec2 point = position;
  switch (behaviour) {
    case RobotBehaviour::kCurious:
      point = robot.center + (robot.radius + radius + config.curious_gap) * away;
      break;
    case RobotBehaviour::kScared:
      return {position + config.notice_distance * away, desired_speed};
    case RobotBehaviour::kThreatening:
      point = robot.center + (robot.radius + radius + config.threatening_gap) * robot.heading;
      break;
    default:
      return {position, 0.0};
  }
  // Keep up with a moving robot, and come to rest on the point.
  const Vec2 to = point - position;
  const double distance = to.norm();
  const double follow = distance > 1e-9 ? std::max(0.0, robot.velocity.dot(to / distance)) : 0.0;
  const double speed = std::min(desired_speed + follow, distance / kArrivalTime + follow);
  return {point, speed};
}

}  // namespace retrace::sim
