#include "nav/map_server.hpp"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "core/check.hpp"
#include "core/config.hpp"
#include "core/errors.hpp"
#include "nav/beam_evidence.hpp"

namespace retrace::nav {
namespace {

std::shared_ptr<const TeachBundle> Linked(TeachBundle bundle, const MapServerConfig& config,
                                          const RouteLinkConfig& link) {
  config.Validate();
  if (bundle.maps.empty()) throw core::ConfigError("maps", "the teach bundle holds no partial map");
  if (!bundle.linked) LinkRoute(bundle, link);
  return std::make_shared<const TeachBundle>(std::move(bundle));
}

// A candidate's heading agrees with the robot's direction of travel (or either is unknown).
bool SameWay(Travel robot, Travel candidate) {
  return robot == Travel::kUnknown || candidate == Travel::kUnknown || robot == candidate;
}

}  // namespace

void MapServerConfig::Validate() const {
  core::RequirePositive("max_sigma", max_sigma);
  core::RequirePositive("min_sigma_xy", min_sigma_xy);
  core::RequirePositive("min_sigma_theta", min_sigma_theta);
  core::RequireIntInRange("settle_updates", settle_updates, 1, 1000);
  core::RequirePositive("settle_rms", settle_rms);
  core::RequireNonNegative("settle_wait", settle_wait);
  core::RequireInRange("min_coverage", min_coverage, 0.0, 1.0);
  core::RequireNonNegative("search_sigma", search_sigma);
}

MapServer::MapServer(TeachBundle bundle, const MapServerConfig& config,
                     const RouteLinkConfig& link, bool loop)
    : bundle_(Linked(std::move(bundle), config, link)),
      config_(config),
      link_(link),
      graph_(bundle_, link.drift) {
  const TeachBundle& b = *bundle_;
  if (loop && !b.maps.back().path.empty() && !b.maps.front().path.empty()) {
    const core::Pose2 end_in_first = LastMapInFirst() * b.maps.back().path.back();
    loops_ = core::Distance(end_in_first, b.maps.front().path.front()) <=
             link_.revisit_radius + link_.drift * graph_.Length();
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

MapDecision MapServer::Decide(const FollowerOutput& f, const RoutePosition& pos,
                              const core::Pose2& X_MR, double max_distance,
                              const ScanPoints* scan, bool lost) const {
  MapDecision d;
  if (scan != nullptr && !scan->xs_L.empty()) d.coverage = Coverage(index_, X_MR, *scan);
  // At the end: the tracked place, or the follower's progress (its goal stays reached once it
  // was: it counts while the robot is at the end).
  const double length = current().path.Length();
  const bool tracked_end = pos.on_path && pos.s_extended >= length - kPathEndTolerance;
  const bool follower_end = pos.s >= length - max_distance && AtPathEnd(f);
  if (pos.travel != Travel::kBackward && (tracked_end || follower_end)) {
    d.travel = Travel::kForward;
    if (!IsLast()) {
      // The common case: path k+1 begins where path k ends, at the switch pose (eq. 1).
      d.step = MapStep::kSwitch;
      d.place = {index_ + 1, TransformToNextMap(current().X_MS, X_MR), current().X_MS.Inverse(),
                 0.0, 0.0, 0.0, false};
      return d;
    }
    if (!loops_) {
      // The route is done while the robot is at its end. A drive that goes on past it (a log
      // replayed beyond the taught route) is placed by the rules below, like any drive off the
      // path.
      if (pos.on_path) {
        d.step = MapStep::kDone;
        return d;
      }
    } else {
      d.step = MapStep::kWrap;
      // Through a revisit edge that closes the loop here, when there is one.
      for (const RoutePlace& p : graph_.Place(index_, X_MR, config_.max_sigma)) {
        if (p.map == 0 && p.via_revisit && p.distance <= max_distance) d.place = p;
      }
      return d;
    }
  }
  if (pos.travel == Travel::kBackward && pos.on_path && pos.s_extended <= kPathEndTolerance &&
      (index_ > 0 || loops_)) {
    const double coverage = d.coverage;
    d = Backward(X_MR);
    d.coverage = coverage;
    return d;
  }
  const bool covered = d.coverage >= config_.min_coverage;
  if (pos.on_path && covered) return d;
  const std::optional<RoutePlace> place = ByPlace(pos, X_MR, max_distance, scan, d.coverage, lost);
  if (place) {
    d.step = MapStep::kSwitch;
    d.place = *place;
    d.travel = TravelOf(bundle_->maps[place->map].path, place->s, place->X_MR.theta);
    if (d.travel == Travel::kUnknown) d.travel = pos.travel;
  } else if (!covered) {
    d.step = MapStep::kOffMap;
  }
  return d;
}

MapDecision MapServer::Backward(const core::Pose2& X_MR) const {
  MapDecision d;
  d.travel = Travel::kBackward;
  if (index_ > 0) {
    // Path k begins where path k-1 ends: eq. (1) inverted, X_{M_{k-1} R} = X_{M_{k-1} S} X_{M_k R}.
    const PartialMap& previous = bundle_->maps[index_ - 1];
    d.step = MapStep::kSwitch;
    d.place = {index_ - 1, previous.X_MS * X_MR, previous.X_MS, previous.path.Length(), 0.0, 0.0,
               false};
    return d;
  }
  d.step = MapStep::kWrap;
  // Round the loop backward: through a revisit edge that joins map 0's start to the last map.
  for (const RoutePlace& p : graph_.Place(0, X_MR, config_.max_sigma)) {
    if (p.map + 1 == size() && p.via_revisit) d.place = p;
  }
  return d;
}

std::optional<RoutePlace> MapServer::ByPlace(const RoutePosition& pos, const core::Pose2& X_MR,
                                             double max_distance, const ScanPoints* scan,
                                             double coverage, bool lost) const {
  // Off the path the estimate drifts with the odometry: the farther it has driven since, the
  // farther from its estimate and the farther through the graph the place may be.
  const double drifted = link_.drift * pos.off_path_driven;
  const double near_sigma = config_.max_sigma + drifted;
  // Through a transform off by more than that, a map is searched only for a robot off the path
  // that is lost, or in a map that no longer covers the scan.
  const bool blind = !pos.on_path && (lost || coverage < config_.min_coverage);
  const double reach = blind ? std::max(near_sigma, config_.search_sigma) : near_sigma;
  std::optional<RoutePlace> best;
  double best_cost = 0.0;
  for (const RoutePlace& p : graph_.Place(index_, X_MR, reach)) {
    // A transform off by more than max_sigma puts the place up to 2 sigma from the path the
    // robot is on: the settling belief searches that far (Navigator::Seed).
    const double far = p.sigma > near_sigma ? 2.0 * p.sigma : 0.0;
    if (p.distance > max_distance + drifted + far) continue;
    // The current map holds the robot elsewhere on its path only where the route passes the
    // place again: farther along the path than the robot can have driven since it left it.
    if (p.map == index_ &&
        (pos.on_path || std::abs(p.s - pos.s) <= pos.off_path_driven + max_distance)) {
      continue;
    }
    if (scan != nullptr && !scan->xs_L.empty()) {
      const double c = Coverage(p.map, p.X_MR, *scan);
      if (c < config_.min_coverage || (p.map != index_ && c <= coverage && pos.on_path)) continue;
    }
    // A path driven the other way than the robot travels (the other leg of a street the route
    // drove out and back) counts as max_distance farther: it is taken only where no path driven
    // the robot's way is near.
    // Another stretch of the current path was driven at another time: the map's own drift
    // between the two lies between them, as between two maps.
    const double sigma = p.map == index_ ? link_.drift * std::abs(p.s - pos.s) : p.sigma;
    if (sigma > reach) continue;
    const bool same_way =
        SameWay(pos.travel, TravelOf(bundle_->maps[p.map].path, p.s, p.X_MR.theta));
    const double cost = p.distance + sigma + (same_way ? 0.0 : max_distance);
    if (!best || cost < best_cost) {
      best = p;
      best_cost = cost;
    }
  }
  if (best && Searched(*best)) {
    // The hypothesis such a place stands for: the robot on that map's path at s. The transform's
    // error lies mostly across the path (a turn of one map against the other), so the settling
    // belief searches around the path point, not around where the transform put the estimate.
    const core::Vec2 on = bundle_->maps[best->map].path.AtArcLength(best->s).translation();
    best->X_MR = core::Pose2(on.x(), on.y(), best->X_MR.theta);
    best->X_jk = best->X_MR * X_MR.Inverse();
    best->distance = 0.0;
  }
  return best;
}

double MapServer::Coverage(std::size_t map, const core::Pose2& X_MR, const ScanPoints& scan) const {
  RETRACE_CHECK(map < size());
  return GridCoverage(bundle_->maps[map].grid, X_MR * scan.X_RL, scan.xs_L, scan.ys_L);
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
  const bool forward = decision.travel != Travel::kBackward;
  RETRACE_CHECK(forward ? IsLast() : index_ == 0);
  const std::size_t to = forward ? 0 : size() - 1;
  if (decision.place.map == to && decision.place.via_revisit) return decision.place;
  // By the chain over the whole loop, which carries the maps' drift over the route.
  RoutePlace place;
  place.map = to;
  place.X_jk = forward ? LastMapInFirst() : LastMapInFirst().Inverse();
  place.s = forward ? 0.0 : bundle_->maps[to].path.Length();
  place.sigma = std::max(config_.min_sigma_xy, 0.5 * link_.drift * graph_.Length());
  return place;
}

}  // namespace retrace::nav
