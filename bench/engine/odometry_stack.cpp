#include "bench/engine/odometry_stack.hpp"

#include "core/errors.hpp"
#include "nav/map_server.hpp"

namespace retrace::bench {

OdometryStack::OdometryStack(const Scenario& scenario, const nav::TeachBundle& bundle)
    : bundle_(bundle),
      follower_(scenario.config.nav.follower),
      avoidance_(scenario.config.nav.avoidance, scenario.robot) {
  if (bundle_.maps.empty()) throw core::ConfigError("maps", "the teach bundle holds no map");
  follower_.SetPathAt(bundle_.maps[0].path, 0.0);
}

void OdometryStack::OnOdometry(double /*t*/, const core::OdometryDelta& delta) {
  X_MR_ = core::IntegrateOdometry(X_MR_, delta);
}

void OdometryStack::OnScan(const core::LaserScan& scan) {
  latest_scan_ = scan;  // for avoidance only
}

StackOutput OdometryStack::OnControlTick(double /*t*/, double dt) {
  StackOutput out;
  nav::FollowerOutput follow = follower_.Compute(X_MR_, dt);
  const bool at_end = nav::AtPathEnd(follow);
  if (at_end && map_ + 1 < bundle_.maps.size()) {
    MapChange sw;
    sw.from = map_;
    sw.to = map_ + 1;
    sw.X_MkR = X_MR_;
    X_MR_ = nav::TransformToNextMap(bundle_.maps[map_].X_MS, X_MR_);  // eq. (1)
    sw.X_MnR = X_MR_;
    map_ = sw.to;
    follower_.SetPathAt(bundle_.maps[map_].path, 0.0);
    follow = follower_.Compute(X_MR_, dt);
    out.map_change = sw;
  } else if (at_end) {
    out.route_done = true;
  }
  out.drive = {.command = follow.command};
  if (latest_scan_) {
    const nav::AvoidanceOutput a = avoidance_.Filter(follow.command, *latest_scan_);
    out.drive = {a.command, a.modified, a.blocked, a.emergency_stop};
  }
  out.X_MR = X_MR_;
  out.map = map_;
  return out;
}

}  // namespace retrace::bench
