#include "nav/route_graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "core/check.hpp"
#include "core/path_projection.hpp"
#include "nav/likelihood_field.hpp"

namespace retrace::nav {
namespace {

// m: the expected error of a registered revisit edge at its place (about a cell of the maps).
constexpr double kRevisitSigma = 0.1;

// m of route between the route arc length u and the nearest point of the interval [lo, hi].
double GapTo(double u, double lo, double hi) { return std::max({0.0, lo - u, u - hi}); }

}  // namespace

core::PathProjection Project(const core::Path& path, const core::Vec2& p) {
  if (path.size() < 2) {
    core::PathProjection one;
    if (!path.empty()) one.distance = (p - path.positions().front()).norm();
    return one;
  }
  return core::ProjectOntoPath(path.positions(), path.arc_lengths(), p, 0.0, path.Length());
}

RouteGraph::RouteGraph(std::shared_ptr<const TeachBundle> bundle, double drift)
    : bundle_(std::move(bundle)), drift_(drift) {
  RETRACE_CHECK(bundle_ != nullptr && !bundle_->maps.empty());
  offset_.push_back(0.0);
  X_0k_.push_back(core::Pose2::Identity());
  for (const PartialMap& map : bundle_->maps) {
    offset_.push_back(offset_.back() + map.path.Length());
    X_0k_.push_back(X_0k_.back() * map.X_MS);
  }
}

core::Pose2 RouteGraph::Chain(std::size_t a, std::size_t b) const {
  return X_0k_[a].Inverse() * X_0k_[b];
}

void RouteGraph::TryCarry(std::size_t j, const Carry& c, const core::Pose2& X_MkR,
                          double max_sigma, RoutePlace* best) const {
  const PartialMap& map = bundle_->maps[j];
  // The least error this carry can have anywhere on path j.
  const double least =
      c.sigma0 + drift_ * GapTo(c.u_from, offset_[j], offset_[j] + map.path.Length());
  if (least > max_sigma || least >= best->sigma) return;
  const core::Pose2 X_MjR = c.X_jk * X_MkR;
  const core::PathProjection proj = Project(map.path, X_MjR.translation());
  const double sigma = c.sigma0 + drift_ * std::abs(c.u_from - (offset_[j] + proj.s));
  if (sigma > max_sigma || sigma >= best->sigma) return;
  *best = {j, X_MjR, c.X_jk, proj.s, proj.distance, sigma, c.via_revisit};
}

std::vector<RoutePlace> RouteGraph::Place(std::size_t k, const core::Pose2& X_MkR,
                                          double max_sigma) const {
  RETRACE_CHECK(k < size());
  const core::PathProjection own = Project(bundle_->maps[k].path, X_MkR.translation());
  const double u_k = offset_[k] + own.s;
  std::vector<RoutePlace> best(size());
  for (std::size_t j = 0; j < size(); ++j) {
    best[j].map = j;
    best[j].sigma = std::numeric_limits<double>::infinity();
  }
  best[k] = {k, X_MkR, core::Pose2::Identity(), own.s, own.distance, 0.0, false};
  // By the chain of switch poses: the drift of the whole route between the two places.
  for (std::size_t j = 0; j < size(); ++j) {
    if (j != k) TryCarry(j, {Chain(j, k), 0.0, u_k, false}, X_MkR, max_sigma, &best[j]);
  }
  // Through a revisit edge of map k: exact at its place, then the chain from the other map.
  for (const RevisitEdge& e : bundle_->revisits) {
    if (e.a != k && e.b != k) continue;
    const bool from_a = e.a == k;
    const std::size_t m = from_a ? e.b : e.a;
    const double s_here = from_a ? e.s_a : e.s_b;
    const double s_there = from_a ? e.s_b : e.s_a;
    const double sigma0 = kRevisitSigma + drift_ * std::abs(own.s - s_here);
    if (sigma0 > max_sigma) continue;
    const core::Pose2 X_mk = from_a ? e.X_ab.Inverse() : e.X_ab;
    for (std::size_t j = 0; j < size(); ++j) {
      if (j == k) continue;
      TryCarry(j, {Chain(j, m) * X_mk, sigma0, offset_[m] + s_there, true}, X_MkR, max_sigma,
               &best[j]);
    }
  }
  std::vector<RoutePlace> out;
  for (const RoutePlace& p : best) {
    if (std::isfinite(p.sigma)) out.push_back(p);
  }
  return out;
}

std::vector<core::Pose2> RouteGraph::PosesInReach(std::size_t k, double max_sigma) const {
  RETRACE_CHECK(k < size());
  std::vector<core::Pose2> out = bundle_->maps[k].path.poses();
  const double lo = offset_[k], hi = offset_[k + 1];
  for (std::size_t j = 0; j < size(); ++j) {
    if (j == k) continue;
    const core::Path& path = bundle_->maps[j].path;
    const core::Pose2 X_kj = Chain(k, j);
    for (std::size_t i = 0; i < path.size(); ++i) {
      if (drift_ * GapTo(offset_[j] + path.ArcLength(i), lo, hi) <= max_sigma)
        out.push_back(X_kj * path[i]);
    }
  }
  for (const RevisitEdge& e : bundle_->revisits) {
    if (e.a != k && e.b != k) continue;
    const bool from_a = e.a == k;
    const core::Path& path = bundle_->maps[from_a ? e.b : e.a].path;
    const double s_there = from_a ? e.s_b : e.s_a;
    const core::Pose2 X_km = from_a ? e.X_ab : e.X_ab.Inverse();
    for (std::size_t i = 0; i < path.size(); ++i) {
      if (kRevisitSigma + drift_ * std::abs(path.ArcLength(i) - s_there) <= max_sigma)
        out.push_back(X_km * path[i]);
    }
  }
  return out;
}

void LinkRoute(TeachBundle& bundle, const RouteLinkConfig& config) {
  bundle.revisits.clear();
  bundle.linked = true;
  if (bundle.maps.size() < 2) return;
  // The chain's frames and offsets only: a graph that does not own the bundle.
  const RouteGraph graph(std::shared_ptr<const TeachBundle>(std::shared_ptr<void>(), &bundle),
                         config.drift);
  std::vector<std::unique_ptr<LikelihoodField>> fields(bundle.maps.size());
  const double step = std::max(0.25, config.revisit_radius / 4.0);
  for (std::size_t b = 1; b < bundle.maps.size(); ++b) {
    const PartialMap& map_b = bundle.maps[b];
    for (std::size_t a = 0; a < b; ++a) {
      const PartialMap& map_a = bundle.maps[a];
      if (map_a.path.size() < 2 || map_b.path.size() < 2) continue;
      const core::Pose2 X_ab = graph.Chain(a, b);
      double next_s = 0.0;  // the next edge of this pair lies at or beyond this arc of path b
      for (double s_b = 0.0; s_b <= map_b.path.Length(); s_b += step) {
        if (s_b < next_s) continue;
        const core::Vec2 p_b = map_b.path.AtArcLength(s_b).translation();
        const core::Vec2 q_a = (X_ab * core::Pose2(p_b.x(), p_b.y(), 0.0)).translation();
        const core::PathProjection on_a = Project(map_a.path, q_a);
        const double driven = std::abs(graph.Offset(b) + s_b - graph.Offset(a) - on_a.s);
        const double drift = config.drift * driven;
        if (drift < config.min_drift || on_a.distance > config.revisit_radius + drift) continue;
        if (!fields[a]) {
          fields[a] = std::make_unique<LikelihoodField>(map_a.grid, LikelihoodFieldConfig{},
                                                        config.registration.radius * 4.0);
        }
        MapRegistrationConfig registration = config.registration;
        registration.search_xy = std::clamp(drift, registration.search_xy, 3.0);
        const std::optional<MapRegistration> r =
            RegisterMaps(*fields[a], map_b.grid, p_b, X_ab, registration);
        if (!r) {
          next_s = s_b + config.spacing / 2.0;  // the place did not register: try farther on
          continue;
        }
        const core::Vec2 registered = (r->X_AB * core::Pose2(p_b.x(), p_b.y(), 0.0)).translation();
        bundle.revisits.push_back({a, b, Project(map_a.path, registered).s, s_b, r->X_AB});
        next_s = s_b + config.spacing;
      }
    }
  }
}

}  // namespace retrace::nav
