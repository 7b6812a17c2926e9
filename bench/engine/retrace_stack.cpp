#include "bench/engine/retrace_stack.hpp"

#include "core/angle.hpp"

namespace retrace::bench {
namespace {

std::optional<MapChange> ChangeOf(const std::optional<nav::MapSwitch>& sw) {
  if (!sw) return std::nullopt;
  return MapChange{sw->from, sw->to, sw->X_MkR, sw->X_MnR};
}

nav::Navigator StartNavigator(const Scenario& scenario, const nav::TeachBundle& bundle,
                              const core::Rng& rng) {
  const ScenarioConfig& config = scenario.config;
  // A playback run drives the route once: it does not loop.
  nav::Navigator nav(config.nav.localizer, config.nav.follower, scenario.robot, bundle,
                     config.nav.map_server, config.route.Link(), false, rng.Split("localizer"));
  nav.Start(0, core::Pose2::Identity(), config.playback.initial_sigma_xy,
            core::DegToRad(config.playback.initial_sigma_yaw_deg));
  return nav;
}

}  // namespace

RetraceStack::RetraceStack(const Scenario& scenario, const nav::TeachBundle& bundle,
                           const core::Rng& rng)
    : nav_(StartNavigator(scenario, bundle, rng)),
      avoidance_(scenario.config.nav.avoidance, scenario.robot) {}

void RetraceStack::OnOdometry(double /*t*/, const core::OdometryDelta& delta) {
  nav_.OnOdometry(delta);
}

void RetraceStack::OnScan(const core::LaserScan& scan) {
  update_ = nav_.OnScan(scan);
  latest_scan_ = scan;
}

StackOutput RetraceStack::OnControlTick(double /*t*/, double dt) {
  const nav::NavigatorTick tick = nav_.OnControlTick(dt);
  StackOutput out;
  out.drive = {.command = tick.follow.command};
  if (latest_scan_) {
    const nav::AvoidanceOutput a = avoidance_.Filter(tick.follow.command, *latest_scan_);
    out.drive = {a.command, a.modified, a.blocked, a.emergency_stop};
  }
  Report(&out);
  out.route_done = tick.route_done;
  out.map_change = ChangeOf(tick.map_switch);
  return out;
}

std::optional<MapChange> RetraceStack::Resume(StackOutput* out) {
  const std::optional<nav::MapSwitch> sw = nav_.Resume();
  Report(out);
  return ChangeOf(sw);
}

void RetraceStack::Report(StackOutput* out) const {
  out->X_MR = nav_.Estimate();
  out->map = nav_.server().index();
  out->lost = nav_.localizer().lost();
  out->off_map = nav_.off_map();
}

}  // namespace retrace::bench
