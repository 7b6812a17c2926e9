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
#include <span>
#include <vector>

#include "core/pose2.hpp"
#include "nav/localizer.hpp"
#include "nav/path_follower.hpp"
#include "nav/route_graph.hpp"
#include "nav/route_position.hpp"
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

/// The map server's options (`nav.map_server`). How far the route graph carries a transform,
/// how a switch through an uncertain transform settles, and how much of a scan a map must cover
/// to hold the robot. The route's drift and revisit radius come from `route.online_drift` and
/// `route.revisit_radius` (RouteLinkConfig), whether it loops from how it is driven.
struct MapServerConfig {
  /// m: the largest expected error of a transform the graph composes: farther along the route
  /// (at 3 % drift, 33 m of route between the two places) a map is not handed over by place.
  double max_sigma = 1.0;
  /// After a switch whose transform may be off by σ > min_sigma_xy, the particles are spread
  /// over σ (and min_sigma_theta in heading), and the scans find the robot again.
  double min_sigma_xy = 0.1;        ///< m
  double min_sigma_theta = 0.0873;  ///< rad: the odometry's 1 % scale error over a full turn
  /// Such a switch settles before it commits (nav::Navigator): a second belief, spread in the
  /// map entered, takes the same odometry and scans while the estimate stays in the map left.
  /// The switch commits once that belief has had settle_updates updates, its particles lie
  /// within settle_rms of their mean (weighted RMS distance), and the scans confirm it: over
  /// the scans both beliefs weighed, the map entered explains them at least as well as the map
  /// left (the sum of the log ratios of their average per-beam likelihoods is >= 0). After
  /// settle_wait s it commits if confirmed and is abandoned if not (a loop's wrap, with no path
  /// left to stay on, commits). One update is not enough: resampling can gather a wide cloud in
  /// one place, right or not, at once. So the estimate the robot drives on never converges in
  /// the new map by a jump, nor enters a map the scans do not support.
  int settle_updates = 3;
  double settle_rms = 0.2;    ///< m
  double settle_wait = 10.0;  ///< s
  /// A map covers the robot's place when at least this share of the scan's tested beams end in
  /// cells it observed (nav/beam_evidence.hpp). Below it, another map that covers the place
  /// takes over; where none does, the robot is off map: odometry only, until a map covers it.
  /// Low: in a room the teaching never entered, the beams through its door that reach mapped
  /// walls still hold the belief (Intel, consistent map, seeds 1-10: 10/10 under 1 m at 0.1,
  /// 9/10 at 0.2, 22/40 at 0.3).
  double min_coverage = 0.1;
  /// m: off the current path, lost or in a map that no longer covers the scan, a map whose transform may be off by more than max_sigma (a street the route drove
  /// again much later, through maps that drifted apart) is still a candidate up to this: the
  /// robot on that map's path, within 2 σ of where the transform carries the estimate, searched
  /// by scan matching and confirmed by settle_wait s of scans before it commits. Measured on the campus driven backwards (partial maps): the street the
  /// reversed drive turns into lay 7.9 m from where map 1's estimate carried it in map 2,
  /// σ = 3.7 m. 0 turns it off.
  double search_sigma = 4.0;

  template <class V>
  void Reflect(V& v) {
    v("max_sigma", max_sigma);
    v("min_sigma_xy", min_sigma_xy);
    v("min_sigma_theta", min_sigma_theta);
    v("settle_updates", settle_updates);
    v("settle_rms", settle_rms);
    v("settle_wait", settle_wait);
    v("min_coverage", min_coverage);
    v("search_sigma", search_sigma);
  }
  /// Throws core::ConfigError naming the key: sigmas and settle_rms > 0, settle_wait >= 0,
  /// settle_updates >= 1, min_coverage in [0, 1], search_sigma >= 0.
  void Validate() const;
};

/// The end points (LiDAR frame) of a scan's tested beams, and where the LiDAR sits on the robot:
/// what the map server needs to tell whether a map covers the scene.
struct ScanPoints {
  std::span<const double> xs_L;
  std::span<const double> ys_L;
  core::Pose2 X_RL;
};

/// What the map server does at a control tick (MapServer::Decide).
enum class MapStep {
  kStay,    ///< the robot is on the current path, or on no other
  kSwitch,  ///< the robot is on another map's path: `place` says which and where
  kWrap,    ///< past an end of a loop's route (MapServer::loops): round to its other end
  kDone,    ///< at the end of the last path: the route is done
  kOffMap,  ///< no map covers the robot's place: odometry only
};

struct MapDecision {
  MapStep step = MapStep::kStay;
  RoutePlace place;  ///< kSwitch, and kWrap through a revisit edge: the map entered and where
  /// The direction of travel on the path entered (kSwitch, kWrap): forward at the next map's
  /// start, backward at the previous map's end, by the estimate's heading for a switch by place.
  Travel travel = Travel::kUnknown;
  /// The share of the scan's beams the current map covers (1 without a scan).
  double coverage = 1.0;
};

class MapServer {
 public:
  /// Takes the teach bundle (its revisits are searched for here with `link` if it was never
  /// linked, nav::LinkRoute; link.drift is the graph's drift). `loop`: the route is driven again
  /// after its last map, as a log that goes round a loop lap after lap, when its last path ends,
  /// through a revisit edge or the chain of switch poses, within link.revisit_radius + drift ×
  /// the route's length of map 0's start. Throws core::ConfigError for an invalid config or a
  /// bundle without maps.
  MapServer(TeachBundle bundle, const MapServerConfig& config, const RouteLinkConfig& link,
            bool loop);

  std::size_t index() const { return index_; }
  std::size_t size() const { return bundle_->maps.size(); }
  bool IsLast() const { return index_ + 1 == bundle_->maps.size(); }
  const PartialMap& current() const { return bundle_->maps[index_]; }
  const PartialMap& map(std::size_t k) const { return bundle_->maps.at(k); }
  const TeachBundle& bundle() const { return *bundle_; }
  const RouteGraph& graph() const { return graph_; }
  /// The route is a loop and is driven again after its last map (the constructor's `loop`).
  bool loops() const { return loops_; }

  /// The map whose taught path lies nearest the robot at X_M0R (a pose in map 0's frame,
  /// carried through the graph without a bound on the transform's error), and the pose there.
  RoutePlace NearestMap(const core::Pose2& X_M0R) const;
  /// Hands map `map` and its path to the localizer and the follower (the start of a run), the
  /// follower's progress at the robot's place X_MR on the path.
  void Start(Localizer& localizer, PathFollower& follower, std::size_t map = 0,
             const core::Pose2& X_MR = core::Pose2::Identity());
  /// The one rule, on the robot's place on the route (`position`, tracked along the current
  /// path: nav/route_position.hpp) and, when given, the scan's tested beams:
  ///  - travelling forward at the end of the current path (the follower's goal reached, or
  ///    within kPathEndTolerance of the end): the next map at the start of its path, by eq. (1);
  ///    after the last one, map 0 again for a loop, else done;
  ///  - travelling backward past the start of the current path: the previous map at the end of
  ///    its path, by eq. (1) inverted; before the first one, the last map for a loop;
  ///  - on the current path, in a map that covers the scan (MapServerConfig::min_coverage): stay;
  ///  - off it (farther than max_distance from the path around the robot's place), or in a map
  ///    that no longer covers the scan: the map whose path the estimate, carried through the
  ///    graph, lies within max_distance of, going the same way as the robot travels, and that
  ///    covers the scan (the nearest counting the transform's expected error); the current map
  ///    at another part of its path counts too. Off the path, `lost` (by the localizer's own
  ///    account) or where the current map does not cover the scan, a transform off by up to
  ///    search_sigma counts too, its place within 2 σ of that map's path. None, and the current map does not cover the scan: off map. None,
  ///    and it does: stay.
  MapDecision Decide(const FollowerOutput& follower_output, const RoutePosition& position,
                     const core::Pose2& X_MR, double max_distance,
                     const ScanPoints* scan = nullptr, bool lost = false) const;
  /// The share of the scan's beams that end in cells map `map` observed, for the robot at X_MR
  /// in that map (nav::GridCoverage).
  double Coverage(std::size_t map, const core::Pose2& X_MR, const ScanPoints& scan) const;
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
  /// A place through a transform off by more than max_sigma (MapServerConfig::search_sigma): it
  /// stands for the robot on that map's path, and its settling belief must end there.
  bool Searched(const RoutePlace& place) const { return place.sigma > config_.max_sigma; }
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
  /// Where a kWrap enters the route's other end: from the end of the last path to map 0
  /// (forward), or from the start of map 0 to the last map (backward). Through the revisit edge
  /// that closes the loop when Decide found one (decision.place), else by the chain,
  /// X_{M_0 R} = LastMapInFirst() * X_{M_n R} (or its inverse), with the particles spread over
  /// the drift the chain may hold (drift × the route's length as two standard deviations).
  RoutePlace WrapPlace(const MapDecision& decision) const;
  const MapServerConfig& config() const { return config_; }

 private:
  // Hands the current map's grid and path over; recovery's poses: the taught paths within
  // reach through the graph.
  void HandOver(Localizer& localizer, PathFollower& follower, double s);
  // Switch and Commit: place.map becomes current, the localizer carried by eq. (1) (and spread
  // over place.sigma) or replaced by a settled belief, the follower on its path at place.s.
  MapSwitch Enter(const RoutePlace& place, Localizer& localizer, PathFollower& follower,
                  Localizer* settled);

  // The backward rule: the previous map at the end of its path, or round a loop to the last.
  MapDecision Backward(const core::Pose2& X_MR) const;
  // The by-place rule: the best map the estimate carried through the graph lies on.
  std::optional<RoutePlace> ByPlace(const RoutePosition& position, const core::Pose2& X_MR,
                                    double max_distance, const ScanPoints* scan, double coverage,
                                    bool lost) const;

  std::shared_ptr<const TeachBundle> bundle_;
  MapServerConfig config_;
  RouteLinkConfig link_;
  RouteGraph graph_;
  bool loops_ = false;
  std::size_t index_ = 0;
};

}  // namespace retrace::nav
