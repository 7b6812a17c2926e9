#pragma once
// The taught route as a graph of partial maps (docs/METHOD.md, "The route as a graph of maps").
// Each map is a vertex with its taught path. Two kinds of edges relate their frames:
//
//  - the switch poses: map k+1 starts at X_{M_k S}, so X_{M_k M_{k+1}} = X_{M_k S} (eq. 1),
//    exact at the switch place;
//  - revisits: places where the route comes back to another map's path, each with the transform
//    measured there by registering the two maps (TeachBundle::revisits, LinkRoute below).
//
// A transform is exact only at the place of its edge. Carried elsewhere it is off by the odometry
// drift of the teaching drive between the two places, which this graph models as `drift` times
// the distance driven between them (the route's arc length): X_{M_j M_k} composed over the chain
// of switch poses is locally consistent for places a few metres of route apart and useless for
// places a lap apart. The graph therefore composes transforms only along short chains: Place()
// carries a pose into every map it reaches with an expected error below a bound, by the chain of
// switch poses or through a revisit edge near the robot, whichever is expected to be better.

#include <cstddef>
#include <memory>
#include <vector>

#include "core/path.hpp"
#include "core/path_projection.hpp"
#include "core/pose2.hpp"
#include "nav/map_registration.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::nav {

/// Where p lies on a taught path, over its whole length (a path of one pose: s = 0 and the
/// distance to it; none: s = 0, distance +inf).
core::PathProjection Project(const core::Path& path, const core::Vec2& p);

/// A robot pose carried into one map of the route.
struct RoutePlace {
  std::size_t map = 0;
  core::Pose2 X_MR;      ///< the pose in that map
  core::Pose2 X_jk;      ///< the transform used: that map's frame from the robot's map's
  double s = 0.0;        ///< m: arc length of the pose's projection onto that map's path
  double distance = 0.0;  ///< m: from the pose to that path
  double sigma = 0.0;    ///< m: the transform's expected error at this place (0 in its own map)
  bool via_revisit = false;  ///< carried through a revisit edge
};

class RouteGraph {
 public:
  /// drift: odometry error per metre of the teaching drive (a fraction, route.online_drift).
  RouteGraph(std::shared_ptr<const TeachBundle> bundle, double drift);

  std::size_t size() const { return bundle_->maps.size(); }
  /// X_{M_a M_b} by the chain of switch poses.
  core::Pose2 Chain(std::size_t a, std::size_t b) const;
  /// m of route driven before map k began (the sum of the earlier paths' lengths).
  double Offset(std::size_t k) const { return offset_[k]; }
  /// The length of the whole taught route (m).
  double Length() const { return offset_.back(); }

  /// The robot at X_MkR in map k, carried into every map (k included) that a transform reaches
  /// with an expected error of at most max_sigma, by the best such transform; with its
  /// projection onto that map's path. In order of map index.
  std::vector<RoutePlace> Place(std::size_t k, const core::Pose2& X_MkR, double max_sigma) const;

  /// Where a robot in map k can be, for recovery: the poses of path k, and of every other path
  /// where a transform reaches them from map k with an expected error of at most max_sigma (the
  /// chain of switch poses beyond either end of path k, the other map's path around a revisit
  /// edge of map k), carried into M_k.
  std::vector<core::Pose2> PosesInReach(std::size_t k, double max_sigma) const;

 private:
  // X_{M_j M_k} and its expected error for the place (k, s_k) carried to map j.
  struct Carry {
    core::Pose2 X_jk;
    double sigma0 = 0.0;  // error gathered before map j (edge and drift in map k)
    double u_from = 0.0;  // route arc length the drift in map j is counted from
    bool via_revisit = false;
  };
  void TryCarry(std::size_t j, const Carry& c, const core::Pose2& X_MkR, double max_sigma,
                RoutePlace* best) const;

  std::shared_ptr<const TeachBundle> bundle_;
  double drift_;
  std::vector<double> offset_;          // per map, and the route length last
  std::vector<core::Pose2> X_0k_;       // map k's frame in map 0's, by the chain
};

/// Settings of LinkRoute.
struct RouteLinkConfig {
  double drift = 0.03;          ///< as RouteGraph's (route.online_drift)
  double revisit_radius = 3.0;  ///< m (route.revisit_radius): paths this close are a revisit ...
  /// ... once the drift between the two places is at least this (m): closer along the route, the
  /// chain of switch poses is as good as an edge.
  double min_drift = 0.2;
  double spacing = 20.0;  ///< m of path b between two edges of the same pair of maps
  MapRegistrationConfig registration;
};

/// Searches the bundle's maps for revisits — at most one every `spacing` m along each path (the
/// next place tried `spacing`/2 on when one does not register), the places where
/// it comes within revisit_radius (widened by the drift between the two visits) of an earlier
/// map's path — and registers the maps at each; the accepted ones become bundle.revisits, and
/// bundle.linked is set.
void LinkRoute(TeachBundle& bundle, const RouteLinkConfig& config);

}  // namespace retrace::nav
