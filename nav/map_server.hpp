#pragma once
// The map server of the playback phase (paper §4.3, docs/METHOD.md "The route as a graph of
// maps"): it holds the partial maps and taught paths as a route graph (nav/route_graph.hpp) and
// answers one question at each control tick — which map's taught path is the robot on now? —
// by place. While the robot is on the current path it stays. At the end of path k it hands map
// k+1 and path k+1 to the localizer and the path follower, every particle carried by the paper's
// eq. (1): the common case of the rule. Off the current path, the estimate is carried through the
// graph (the chain of switch poses, or a revisit edge, only where the transform's expected error
// is small) into every map it reaches, and the map whose path the robot is on takes over: the
// previous one for a drive that goes back along the route, or any map the route passes again.
// The same rule serves the simulator's playback and a log's replay.

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "core/pose2.hpp"
#include "nav/localizer.hpp"
#include "nav/path_follower.hpp"
#include "nav/route_graph.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::nav {

/// Paper eq. (1): the pose of the robot in map k+1 from its pose in map k and map k's switch
/// pose X_{M_k S}: X_{M_{k+1} R} = inverse(X_{M_k S}) * X_{M_k R}. The switch pose itself maps
/// to the identity, since map k+1 starts where map k ended.
inline core::Pose2 TransformToNextMap(const core::Pose2& X_MkS, const core::Pose2& X_MkR) {
  return X_MkS.Inverse() * X_MkR;
}

/// What a switch did, for diagnostics and metrics.
struct MapSwitch {
  std::size_t from = 0;  ///< index of the map left
  std::size_t to = 0;    ///< index of the map entered
  core::Pose2 X_MkR;     ///< the estimate in the map left, just before the switch
  core::Pose2 X_MnR;     ///< the estimate in the map entered, just after it
  double sigma = 0.0;    ///< m: the expected error of the transform used (the particles' spread)
};

/// How the map server reads the route graph, and driving the route again after its last map as
/// a log that goes round a loop lap after lap does. The route is a loop when the end of its last
/// path lies, through a revisit edge or the chain of switch poses, within closure_radius + drift
/// × the route's length of map 0's start.
struct MapServerConfig {
  bool loop = false;            ///< a loop is driven again after its last map
  double closure_radius = 3.0;  ///< m (route.revisit_radius)
  double drift = 0.03;          ///< odometry error per metre driven (route.online_drift)
  /// m: the largest expected error of a transform the graph composes: farther along the route
  /// (at 3 % drift, 33 m of route between the two places) a map is not handed over by place.
  double max_sigma = 1.0;
  /// After a switch whose transform may be off by σ > min_sigma_xy, the particles are spread
  /// over σ (and min_sigma_theta in heading), and the scans find the robot again.
  double min_sigma_xy = 0.1;        ///< m
  double min_sigma_theta = 0.0873;  ///< rad: the odometry's 1 % scale error over a full turn
  /// Such a switch settles before it commits (nav::Navigator): a second belief, spread in the
  /// map entered, takes the same odometry and scans while the estimate stays in the map left.
  /// The switch commits once that belief has had settle_updates updates and its particles lie
  /// within settle_rms of their mean (weighted RMS distance), or after settle_wait s whatever
  /// it holds. One update is not enough: resampling can gather a wide cloud in one place, right
  /// or not, at once. So the estimate the robot drives on never converges in the new map by a
  /// jump.
  int settle_updates = 3;
  double settle_rms = 0.2;    ///< m
  double settle_wait = 10.0;  ///< s
};

/// What the map server does at a control tick (MapServer::Decide).
enum class MapStep {
  kStay,    ///< the robot is on the current path, or on no other
  kSwitch,  ///< the robot is on another map's path: `place` says which and where
  kWrap,    ///< at the end of the last path of a loop (MapServerConfig::loop): back to map 0
  kDone,    ///< at the end of the last path: the route is done
};

struct MapDecision {
  MapStep step = MapStep::kStay;
  RoutePlace place;  ///< kSwitch, and kWrap through a revisit edge: the map entered and where
};

class MapServer {
 public:
  /// The estimate counts as at the end of its path within this much arc length of it (m), or
  /// when the follower says its goal is reached.
  static constexpr double kPathEndTolerance = 0.05;

  /// Takes the teach bundle (its revisits are searched for here if it was never linked,
  /// nav::LinkRoute). Throws core::ConfigError if it holds no map.
  explicit MapServer(TeachBundle bundle, const MapServerConfig& config = {});

  std::size_t index() const { return index_; }
  std::size_t size() const { return bundle_->maps.size(); }
  bool IsLast() const { return index_ + 1 == bundle_->maps.size(); }
  const PartialMap& current() const { return bundle_->maps[index_]; }
  const TeachBundle& bundle() const { return *bundle_; }
  const RouteGraph& graph() const { return graph_; }
  /// The route is a loop and is driven again after its last map (MapServerConfig).
  bool loops() const { return loops_; }

  /// The map whose taught path lies nearest the robot at X_M0R (a pose in map 0's frame,
  /// carried through the graph without a bound on the transform's error), and the pose there.
  RoutePlace NearestMap(const core::Pose2& X_M0R) const;
  /// Hands map `map` and its path to the localizer and the follower (the start of a run), the
  /// follower's progress at the robot's place X_MR on the path.
  void Start(Localizer& localizer, PathFollower& follower, std::size_t map = 0,
             const core::Pose2& X_MR = core::Pose2::Identity());
  /// The one rule. At the end of the current path (follower goal reached, or within
  /// kPathEndTolerance of the end): the next map, entered at the robot's place on its path;
  /// after the last one, map 0 again for a loop that is driven again, else done. Off the current
  /// path (the follower's progress waits) and farther than max_distance from all of it: the map
  /// whose path the estimate, carried through the graph, lies within max_distance of (the nearest
  /// counting the transform's expected error), if any. Otherwise stay.
  MapDecision Decide(const FollowerOutput& follower_output, const core::Pose2& X_MR,
                     double max_distance) const;
  /// Where the robot is on the route now, whatever the follower's progress (an operator drove
  /// it and hands it back): the map whose taught path lies nearest the estimate through the
  /// graph (the current one included, transforms within max_sigma), entered at the robot's place.
  RoutePlace Resume(const core::Pose2& X_MR) const;
  /// Carries out a kSwitch: the localizer gets the map with every particle and the estimate
  /// moved by place.X_jk (eq. (1) for the next map), spread over place.sigma when that exceeds
  /// min_sigma_xy; the follower gets its path with the progress at place.s.
  MapSwitch Switch(const RoutePlace& place, Localizer& localizer, PathFollower& follower);
  /// A switch settles first (MapServerConfig::settle_rms) when it enters another map by a
  /// transform whose expected error exceeds min_sigma_xy. (A wrap within one map, as in a single
  /// or consistent map, spreads the belief where it is: there is no other map to settle in.)
  bool Settles(const RoutePlace& place) const {
    return place.map != index_ && place.sigma > config_.min_sigma_xy;
  }
  /// The belief a settling switch starts from: `belief` gets place.map's grid and recovery poses,
  /// and particles spread over place.sigma around the estimate X_MkR carried by place.X_jk.
  void Prepare(const RoutePlace& place, const core::Pose2& X_MkR, Localizer& belief) const;
  /// Commits a settled switch: place.map becomes current, `settled` (Prepare'd for it, and
  /// updated since) replaces the localizer, the follower gets its path at place.s.
  MapSwitch Commit(const RoutePlace& place, Localizer&& settled, Localizer& localizer,
                   PathFollower& follower);

  /// For a route driven again and again (a loop): the last map's frame in map 0's, chained
  /// through the switch poses by eq. (1), X_{M_0 M_n} = X_{M_0 S_0} * ... * X_{M_{n-1} S_{n-1}}
  /// (the identity for one map). It carries the drift the maps accumulated over the route.
  core::Pose2 LastMapInFirst() const { return graph_.Chain(0, size() - 1); }
  /// From the end of the last path back to map 0 and path 0 (the loop driven again): through
  /// the revisit edge that closes the loop when Decide found one (`place`), else by the chain,
  /// X_{M_0 R} = LastMapInFirst() * X_{M_n R}, with the particles spread over the drift the
  /// chain may hold (drift × the route's length as two standard deviations). Requires IsLast().
  MapSwitch WrapToFirst(const MapDecision& decision, Localizer& localizer, PathFollower& follower) {
    return Switch(WrapPlace(decision), localizer, follower);
  }
  /// Where a kWrap enters map 0: through its revisit edge, else by the chain with its sigma.
  RoutePlace WrapPlace(const MapDecision& decision) const;
  const MapServerConfig& config() const { return config_; }

 private:
  // Hands the current map's grid and path over; recovery's poses: the taught paths within
  // reach through the graph.
  void HandOver(Localizer& localizer, PathFollower& follower, double s);
  std::vector<core::Pose2> PosesInReach() const;
  // Switch and Commit: place.map becomes current, the localizer carried by eq. (1) (and spread
  // over place.sigma) or replaced by a settled belief, the follower on its path at place.s.
  MapSwitch Enter(const RoutePlace& place, Localizer& localizer, PathFollower& follower,
                  Localizer* settled);

  std::shared_ptr<const TeachBundle> bundle_;
  MapServerConfig config_;
  RouteGraph graph_;
  bool loops_ = false;
  std::size_t index_ = 0;
};

}  // namespace retrace::nav
