#include "nav/navigator.hpp"

#include <utility>

namespace retrace::nav {

Navigator::Navigator(const LocalizerConfig& localizer, const PathFollowerConfig& follower,
                     const RobotGeometry& robot, TeachBundle bundle,
                     const MapServerConfig& server, core::Rng localizer_rng)
    : localizer_(localizer, robot, localizer_rng),
      follower_(follower),
      server_(std::move(bundle), server) {}

void Navigator::Start(std::size_t map, const core::Pose2& X_MR, double sigma_xy,
                      double sigma_theta) {
  server_.Start(localizer_, follower_, map, X_MR);
  localizer_.Initialize(X_MR, sigma_xy, sigma_theta);
}

void Navigator::StartNearest(const core::Pose2& X_M0R, double sigma_xy, double sigma_theta) {
  const RoutePlace place = server_.NearestMap(X_M0R);
  Start(place.map, place.X_MR, sigma_xy, sigma_theta);
}

std::optional<MapSwitch> Navigator::Resume() {
  const RoutePlace place = server_.Resume(localizer_.Estimate());
  if (place.map != server_.index()) return server_.Switch(place, localizer_, follower_);
  follower_.SetPathAt(server_.current().path, place.s);
  return std::nullopt;
}

LocalizerUpdate Navigator::OnScan(const core::LaserScan& scan) {
  LocalizerUpdate update = localizer_.Update(scan);
  if (update.reacquired) {
    confirming_ = localizer_.config().augmented.confirm_updates;
  } else if (update.ran && !update.lost && confirming_ > 0) {
    --confirming_;
  }
  return update;
}

NavigatorTick Navigator::OnControlTick(double dt) {
  NavigatorTick tick;
  tick.follow = follower_.Compute(localizer_.Estimate(), dt);
  const MapDecision decision = server_.Decide(tick.follow, localizer_.Estimate(),
                                              follower_.config().progress_max_distance);
  switch (decision.step) {
    case MapStep::kStay:
      break;
    case MapStep::kDone:
      tick.route_done = true;
      break;
    case MapStep::kSwitch:
      tick.map_switch = server_.Switch(decision.place, localizer_, follower_);
      tick.follow = follower_.Compute(localizer_.Estimate(), dt);
      break;
    case MapStep::kWrap:
      tick.map_switch = server_.WrapToFirst(decision, localizer_, follower_);
      tick.wrapped = true;
      tick.follow = follower_.Compute(localizer_.Estimate(), dt);
      break;
  }
  const double creep = follower_.config().creep_speed;
  core::Twist& command = tick.follow.command;
  if ((localizer_.lost() || confirming_ > 0) && command.v > creep) {
    command.omega *= creep / command.v;
    command.v = creep;
    tick.creeping = true;
  }
  return tick;
}

}  // namespace retrace::nav
