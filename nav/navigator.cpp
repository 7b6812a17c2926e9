#include "nav/navigator.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "nav/cluster_estimate.hpp"
#include "nav/place_search.hpp"

namespace retrace::nav {

Navigator::Navigator(const LocalizerConfig& localizer, const PathFollowerConfig& follower,
                     const RobotGeometry& robot, TeachBundle bundle, const MapServerConfig& server,
                     const RouteLinkConfig& link, bool loop, core::Rng localizer_rng)
    : localizer_(localizer, robot, localizer_rng),
      follower_(follower),
      server_(std::move(bundle), server, link, loop),
      settle_rng_(localizer_rng.Split("settle")) {}

void Navigator::Start(std::size_t map, const core::Pose2& X_MR, double sigma_xy,
                      double sigma_theta) {
  pending_.reset();
  off_map_ = false;
  server_.Start(localizer_, follower_, map, X_MR);
  localizer_.Initialize(X_MR, sigma_xy, sigma_theta);
  Track(Project(server_.current().path, X_MR.translation()).s, Travel::kUnknown);
}

void Navigator::Track(double s, Travel travel) {
  tracker_.Reset(server_.current().path, server_.index(), s, localizer_.Estimate(), travel);
}

void Navigator::StartNearest(const core::Pose2& X_M0R, double sigma_xy, double sigma_theta) {
  const RoutePlace place = server_.NearestMap(X_M0R);
  Start(place.map, place.X_MR, sigma_xy, sigma_theta);
}

std::optional<MapSwitch> Navigator::Resume() {
  pending_.reset();
  off_map_ = false;
  const RoutePlace place = server_.Resume(localizer_.Estimate());
  std::optional<MapSwitch> s;
  if (place.map != server_.index()) {
    s = server_.Switch(place, localizer_, follower_);
  } else {
    follower_.SetPathAt(server_.current().path, place.s);
  }
  Track(place.s, Travel::kUnknown);
  return s;
}

void Navigator::OnOdometry(const core::OdometryDelta& delta) {
  localizer_.Predict(delta);
  if (pending_) pending_->belief.Predict(delta);
}

LocalizerUpdate Navigator::OnScan(const core::LaserScan& scan) {
  ScanEndPoints(scan, localizer_.robot(), localizer_.config().beam_step, &scan_xs_, &scan_ys_);
  LocalizerUpdate settling;
  if (pending_) {
    if (!pending_->seeded) Seed(scan);
    settling = pending_->belief.Update(scan);
    if (settling.ran) ++pending_->updates;
  }
  if (off_map_) return {};  // odometry only: no map explains the scan
  LocalizerUpdate update = localizer_.Update(scan);
  if (pending_ && settling.ran && update.ran && settling.w_avg > 0.0 && update.w_avg > 0.0) {
    // The two beliefs on the same scan: which map explains what the robot sees?
    pending_->evidence += std::log(settling.w_avg) - std::log(update.w_avg);
  }
  if (update.reacquired) {
    confirming_ = localizer_.config().augmented.confirm_updates;
  } else if (update.ran && !update.lost && confirming_ > 0) {
    --confirming_;
  }
  return update;
}

NavigatorTick Navigator::OnControlTick(double dt) {
  NavigatorTick tick;
  const core::Pose2 estimate = localizer_.Estimate();
  tick.follow = follower_.Compute(estimate, dt);
  const PathFollowerConfig& fc = follower_.config();
  const RoutePosition& position =
      tracker_.Update(estimate, fc.progress_window, fc.progress_max_distance);
  const ScanPoints points{scan_xs_, scan_ys_, localizer_.robot().X_RL};
  const MapDecision decision = server_.Decide(tick.follow, position, estimate,
                                              fc.progress_max_distance,
                                              scan_xs_.empty() ? nullptr : &points,
                                              localizer_.misfit());
  tick.coverage = decision.coverage;
  off_map_ = decision.step == MapStep::kOffMap;
  if (pending_) pending_->waited += dt;
  switch (decision.step) {
    case MapStep::kStay:
    case MapStep::kOffMap:
      break;
    case MapStep::kDone:
      pending_.reset();
      tick.route_done = true;
      break;
    case MapStep::kSwitch:
      tick.map_switch = SwitchTo(decision.place, decision.travel, false);
      break;
    case MapStep::kWrap:
      tick.map_switch = SwitchTo(server_.WrapPlace(decision), decision.travel, true);
      break;
  }
  if (pending_ && Abandoned(*pending_)) pending_.reset();
  if (pending_ && Settled(*pending_)) {
    tick.wrapped = pending_->wrap;
    tick.map_switch =
        server_.Commit(pending_->place, std::move(pending_->belief), localizer_, follower_);
    Track(pending_->place.s, pending_->travel);
    pending_.reset();
  }
  if (tick.map_switch) tick.follow = follower_.Compute(localizer_.Estimate(), dt);
  tick.off_map = off_map_;
  const double creep = fc.creep_speed;
  core::Twist& command = tick.follow.command;
  if ((localizer_.lost() || off_map_ || confirming_ > 0) && command.v > creep) {
    command.omega *= creep / command.v;
    command.v = creep;
    tick.creeping = true;
  }
  return tick;
}

std::optional<MapSwitch> Navigator::SwitchTo(const RoutePlace& place, Travel travel, bool wrap) {
  if (place.map == server_.index() && !wrap) {
    // Another stretch of the current path (a street its map drove twice): no switch, the
    // follower and the place move there.
    pending_.reset();
    follower_.SetPathAt(server_.current().path, place.s);
    Track(place.s, travel);
    return std::nullopt;
  }
  if (!server_.Settles(place)) {
    pending_.reset();
    MapSwitch s = server_.Switch(place, localizer_, follower_);
    Track(place.s, travel);
    return s;
  }
  if (pending_ && pending_->place.map == place.map) {
    pending_->place.s = place.s;  // the robot's progress on that path now
    pending_->travel = travel;
    return std::nullopt;
  }
  const core::Rng rng = settle_rng_.Split(settles_++);
  Localizer belief(localizer_.config(), localizer_.robot(), rng.Split("belief"));
  server_.Prepare(place, localizer_.Estimate(), belief);
  pending_.emplace(PendingSwitch{place, std::move(belief), rng.Split("seed"), travel, wrap});
  return std::nullopt;
}

void Navigator::Seed(const core::LaserScan& scan) {
  PendingSwitch& p = *pending_;
  p.seeded = true;
  const LocalizerConfig& config = localizer_.config();
  std::vector<double> xs, ys;
  ScanEndPoints(scan, localizer_.robot(), config.beam_step, &xs, &ys);
  const double sigma = std::max(p.place.sigma, server_.config().min_sigma_xy);
  const std::vector<ScoredPlace> places =
      SearchPlaces(p.belief.likelihood_field(), localizer_.robot(), xs, ys, p.belief.Estimate(),
                   2.0 * sigma, 2.0 * server_.config().min_sigma_theta);
  if (places.empty()) return;
  const PlaceSearchConfig grid;
  p.belief.SetParticles(
      ParticlesAtPlaces(places, config.particles, grid.step_xy, grid.step_theta, p.rng));
}

bool Navigator::Settled(const PendingSwitch& p) const {
  const MapServerConfig& c = server_.config();
  // Confirmed by the scans: the map entered explains them at least as well as the map left. A
  // loop's wrap has no path left to stay on: it needs no confirmation. A belief that is lost in
  // the map entered confirms nothing; nor does one that settled off the path a searched place
  // stands for.
  const bool on_path =
      !server_.Searched(p.place) ||
      Project(server_.map(p.place.map).path, p.belief.Estimate().translation()).distance <=
          follower_.config().progress_max_distance;
  const bool confirmed = p.wrap || (p.evidence >= 0.0 && !p.belief.lost() && on_path);
  if (p.waited >= c.settle_wait) return confirmed;
  // A searched place may be wrong by metres along a street that looks the same all along: its
  // belief gathers in one place of many at once. It commits only after settle_wait, the scans
  // of that much driving having confirmed it.
  return !server_.Searched(p.place) && confirmed && p.updates >= c.settle_updates &&
         ParticleSpread(p.belief.particles()) <= c.settle_rms;
}

bool Navigator::Abandoned(const PendingSwitch& p) const {
  // A switch by place that the scans did not confirm in settle_wait: the map left explains them
  // better. (A loop's wrap has no path left to stay on: it commits.)
  return !p.wrap && p.waited >= server_.config().settle_wait && !Settled(p);
}

}  // namespace retrace::nav
