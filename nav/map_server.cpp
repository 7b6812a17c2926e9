#include "nav/map_server.hpp"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "core/check.hpp"
#include "core/errors.hpp"

namespace retrace::nav {
namespace {

std::shared_ptr<const TeachBundle> Linked(TeachBundle bundle, const MapServerConfig& config) {
  if (bundle.maps.empty()) throw core::ConfigError("maps", "the teach bundle holds no partial map");
  if (!bundle.linked) {
    RouteLinkConfig link;
    link.drift = config.drift;
    link.revisit_radius = config.closure_radius;
    LinkRoute(bundle, link);
  }
  return std::make_shared<const TeachBundle>(std::move(bundle));
}

}  // namespace

MapServer::MapServer(TeachBundle bundle, const MapServerConfig& config)
    : bundle_(Linked(std::move(bundle), config)), config_(config), graph_(bundle_, config.drift) {
  const TeachBundle& b = *bundle_;
  if (config_.loop && !b.maps.back().path.empty() && !b.maps.front().path.empty()) {
    const core::Pose2 end_in_first = LastMapInFirst() * b.maps.back().path.back();
    loops_ = core::Distance(end_in_first, b.maps.front().path.front()) <=
             config_.closure_radius + config_.drift * graph_.Length();
  }
}

void MapServer::HandOver(Localizer& localizer, PathFollower& follower, double s) {
  follower.SetPathAt(current().path, s);
  localizer.SetRecoveryPoses(graph_.PosesInReach(index_, config_.max_sigma));
}

RoutePlace MapServer::NearestMap(const core::Pose2& X_M0R) const {
  const std::vector<RoutePlace> places =
      graph_.Place(0, X_M0R, std::numeric_limits<double>::infinity());
  return *std::min_element(places.begin(), places.end(),
                           [](const RoutePlace& a, const RoutePlace& b) {
                             return a.distance + a.sigma < b.distance + b.sigma;
                           });
}

void MapServer::Start(Localizer& localizer, PathFollower& follower, std::size_t map,
                      const core::Pose2& X_MR) {
  RETRACE_CHECK(map < size());
  index_ = map;
  localizer.SetMap(current().grid);
  HandOver(localizer, follower, Project(current().path, X_MR.translation()).s);
}

MapDecision MapServer::Decide(const FollowerOutput& f, const core::Pose2& X_MR,
                              double max_distance) const {
  MapDecision d;
  if (f.goal_reached || (f.remaining <= kPathEndTolerance && !f.off_path)) {
    if (!IsLast()) {
      // The common case: path k+1 begins where path k ends, at the switch pose (eq. 1).
      d.step = MapStep::kSwitch;
      d.place = {index_ + 1,
                 TransformToNextMap(current().X_MS, X_MR),
                 current().X_MS.Inverse(),
                 0.0,
                 0.0,
                 0.0,
                 false};
      return d;
    }
    if (!loops_) {
      d.step = MapStep::kDone;
      return d;
    }
    d.step = MapStep::kWrap;
    // Through a revisit edge that closes the loop here, when there is one.
    for (const RoutePlace& p : graph_.Place(index_, X_MR, config_.max_sigma)) {
      if (p.map == 0 && p.via_revisit && p.distance <= max_distance) d.place = p;
    }
    return d;
  }
  if (!f.off_path) return d;
  const std::vector<RoutePlace> places = graph_.Place(index_, X_MR, config_.max_sigma);
  const RoutePlace* best = nullptr;
  for (const RoutePlace& p : places) {
    // Still on the current path, behind the progress or beyond the follower's rejoin window:
    // the map holds the robot.
    if (p.map == index_ && p.distance <= max_distance) return d;
    if (p.map == index_ || p.distance > max_distance) continue;
    if (best == nullptr || p.distance + p.sigma < best->distance + best->sigma) best = &p;
  }
  if (best != nullptr) {
    d.step = MapStep::kSwitch;
    d.place = *best;
  }
  return d;
}

RoutePlace MapServer::Resume(const core::Pose2& X_MR) const {
  const std::vector<RoutePlace> places = graph_.Place(index_, X_MR, config_.max_sigma);
  return *std::min_element(places.begin(), places.end(),
                           [](const RoutePlace& a, const RoutePlace& b) {
                             return a.distance + a.sigma < b.distance + b.sigma;
                           });
}

MapSwitch MapServer::Switch(const RoutePlace& place, Localizer& localizer, PathFollower& follower) {
  return Enter(place, localizer, follower, nullptr);
}

MapSwitch MapServer::Enter(const RoutePlace& place, Localizer& localizer, PathFollower& follower,
                           Localizer* settled) {
  RETRACE_CHECK(place.map < size());
  MapSwitch s;
  s.from = index_;
  s.to = place.map;
  s.X_MkR = localizer.Estimate();
  s.sigma = place.sigma;
  index_ = place.map;
  if (settled != nullptr) {
    localizer = std::move(*settled);
  } else {
    localizer.ApplyMapSwitch(current().grid, place.X_jk);  // eq. (1) for the next map
    if (place.sigma > config_.min_sigma_xy) {
      // The transform may be off by about sigma here: let the scans find the robot again.
      localizer.Initialize(localizer.Estimate(), place.sigma, config_.min_sigma_theta);
    }
  }
  HandOver(localizer, follower, place.s);
  s.X_MnR = localizer.Estimate();
  return s;
}

void MapServer::Prepare(const RoutePlace& place, const core::Pose2& X_MkR,
                        Localizer& belief) const {
  RETRACE_CHECK(place.map < size());
  belief.SetMap(bundle_->maps[place.map].grid);
  belief.SetRecoveryPoses(graph_.PosesInReach(place.map, config_.max_sigma));
  belief.Initialize(place.X_jk * X_MkR, std::max(place.sigma, config_.min_sigma_xy),
                    config_.min_sigma_theta);
}

MapSwitch MapServer::Commit(const RoutePlace& place, Localizer&& settled, Localizer& localizer,
                            PathFollower& follower) {
  return Enter(place, localizer, follower, &settled);
}

RoutePlace MapServer::WrapPlace(const MapDecision& decision) const {
  RETRACE_CHECK(IsLast());
  if (decision.place.map == 0 && decision.place.via_revisit) return decision.place;
  // By the chain over the whole loop, which carries the maps' drift over the route.
  RoutePlace place;
  place.map = 0;
  place.X_jk = LastMapInFirst();
  place.sigma = std::max(config_.min_sigma_xy, 0.5 * config_.drift * graph_.Length());
  return place;
}

}  // namespace retrace::nav
