#include "bench/engine/end_conditions.hpp"

namespace retrace::bench {
namespace {

constexpr double kStallProgress = 0.5;  // m along the path that counts as progress

}  // namespace

EndConditions::EndConditions(const LimitsConfig& limits, double timeout_s)
    : limits_(limits), timeout_s_(timeout_s) {}

std::optional<Outcome> EndConditions::Check(const TickStatus& tick) {
  const double t = tick.time;
  if (tick.operator_driving) {
    lost_since_ = -1.0;
    last_progress_time_ = t;
  } else if (tick.localization_error > limits_.lost_distance) {
    if (lost_since_ < 0.0) lost_since_ = t;
  } else {
    lost_since_ = -1.0;
  }
  if (tick.map_index > best_progress_.first ||
      tick.remaining < best_progress_.second - kStallProgress) {
    best_progress_ = {tick.map_index, tick.remaining};
    last_progress_time_ = t;
  }
  if (tick.goal_reached && tick.last_map) {
    return tick.goal_distance <= limits_.lost_distance ? Outcome::kSuccess : Outcome::kLost;
  }
  if (limits_.stop_on_collision && tick.collided) return Outcome::kCollision;
  if (lost_since_ >= 0.0 && t - lost_since_ >= limits_.lost_time) return Outcome::kLost;
  if (t >= timeout_s_ || t - last_progress_time_ >= limits_.stall_time) return Outcome::kTimeout;
  return std::nullopt;
}

}  // namespace retrace::bench
