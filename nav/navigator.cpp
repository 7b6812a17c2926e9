#include "nav/navigator.hpp"

#include <utility>

namespace retrace::nav {

Navigator::Navigator(const LocalizerConfig& localizer, const PathFollowerConfig& follower,
                     const RobotGeometry& robot, TeachBundle bundle, const LoopConfig& loop,
                     core::Rng localizer_rng)
    : localizer_(localizer, robot, localizer_rng),
      follower_(follower),
      server_(std::move(bundle), loop) {}

void Navigator::Start(const core::Pose2& X_M0R, double sigma_xy, double sigma_theta) {
  server_.Start(localizer_, follower_);
  localizer_.Initialize(X_M0R, sigma_xy, sigma_theta);
}

NavigatorTick Navigator::OnControlTick(double dt) {
  NavigatorTick tick;
  tick.follow = follower_.Compute(localizer_.Estimate(), dt);
  switch (server_.Decide(tick.follow, localizer_.Estimate(),
                         follower_.config().progress_max_distance)) {
    case MapStep::kStay:
      break;
    case MapStep::kDone:
      tick.route_done = true;
      break;
    case MapStep::kNext:
      tick.map_switch = server_.SwitchToNext(localizer_, follower_);
      tick.follow = follower_.Compute(localizer_.Estimate(), dt);
      break;
    case MapStep::kBack:
      tick.map_switch = server_.SwitchBack(localizer_, follower_);
      tick.follow = follower_.Compute(localizer_.Estimate(), dt);
      break;
    case MapStep::kWrap:
      tick.map_switch = server_.WrapToFirst(localizer_, follower_);
      tick.wrapped = true;
      tick.follow = follower_.Compute(localizer_.Estimate(), dt);
      break;
  }
  return tick;
}

}  // namespace retrace::nav
