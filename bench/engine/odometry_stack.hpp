#pragma once
// The baseline without localization: the taught paths replayed on wheel odometry alone. The
// estimate is dead reckoning from map 0's origin (where the robot believes it starts, as
// retrace's navigator does); at the end of path k it moves into map k+1 by the paper's eq. (1),
// and the path follower and obstacle avoidance are retrace's own. Beside retrace's navigator in
// one table, it shows what localization buys.

#include <optional>

#include "bench/stack/navigation_stack.hpp"
#include "bench/engine/scenario.hpp"
#include "nav/obstacle_avoidance.hpp"
#include "nav/path_follower.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::bench {

class OdometryStack final : public NavigationStack {
 public:
  /// Follows `bundle`'s paths (which must outlive the stack) with the scenario's follower and
  /// avoidance settings.
  OdometryStack(const Scenario& scenario, const nav::TeachBundle& bundle);

  void OnOdometry(double t, const core::OdometryDelta& delta) override;
  void OnScan(const core::LaserScan& scan) override;
  StackOutput OnControlTick(double t, double dt) override;

 private:
  const nav::TeachBundle& bundle_;
  nav::PathFollower follower_;
  nav::ObstacleAvoidance avoidance_;
  std::size_t map_ = 0;
  core::Pose2 X_MR_;  // dead reckoning in map map_
  std::optional<core::LaserScan> latest_scan_;
};

}  // namespace retrace::bench
