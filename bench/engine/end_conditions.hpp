#pragma once
// When a playback run ends (docs/DESIGN.md §6): success at the end of the last path, when the
// robot truly is within limits.lost_distance of the taught route's end (a stack that claims the
// goal farther from it is lost: success is never a stack's word alone); or a failure — a collision
// (when limits.stop_on_collision), lost (the estimate farther than limits.lost_distance from the
// local truth for limits.lost_time), or a timeout (the time limit, or no 0.5 m of progress along
// the taught path for limits.stall_time).

#include <cstddef>
#include <limits>
#include <optional>
#include <utility>

#include "bench/engine/scenario.hpp"
#include "bench/engine/trace.hpp"

namespace retrace::bench {

/// What the end conditions look at, once per control tick.
struct TickStatus {
  double time = 0.0;                ///< s since the run started
  bool goal_reached = false;        ///< the follower reached the end of its path ...
  bool last_map = false;            ///< ... and that path is the last one
  bool collided = false;            ///< any contact so far
  double localization_error = 0.0;  ///< m, estimate vs local truth
  double goal_distance = 0.0;       ///< m from the robot (ground truth) to the taught route's end
  std::size_t map_index = 0;        ///< the current map
  double remaining = 0.0;           ///< m of the current path left
  /// An operator drives the robot (a takeover): neither lost nor stalled counts meanwhile.
  bool operator_driving = false;
};

class EndConditions {
 public:
  EndConditions(const LimitsConfig& limits, double timeout_s);

  /// The outcome when the run ends at this tick, nothing otherwise. Call at every control tick.
  std::optional<Outcome> Check(const TickStatus& tick);

 private:
  LimitsConfig limits_;
  double timeout_s_;
  double lost_since_ = -1.0;
  // Progress for the stall check: the maps passed and the path length left in the current one.
  std::pair<std::size_t, double> best_progress_{0, std::numeric_limits<double>::infinity()};
  double last_progress_time_ = 0.0;
};

}  // namespace retrace::bench
