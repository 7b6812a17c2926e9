#pragma once
// The map server of the playback phase (paper §4.3): it holds the sequence of partial maps and
// taught paths, and at the end of path k hands map k+1 and path k+1 to the localizer and the
// path follower, transforming the estimate and every particle by the paper's eq. (1). It owns the
// one rule for when that happens (Decide), for the simulator's playback and a log's replay alike.

#include <cstddef>
#include <vector>

#include "core/pose2.hpp"
#include "nav/localizer.hpp"
#include "nav/path_follower.hpp"
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
  core::Pose2 X_MkR;     ///< the estimate in map k just before the switch
  core::Pose2 X_MnR;     ///< the estimate in map k+1 just after it
};

/// Driving the route again after its last map, as a log that goes round a loop lap after lap
/// does. The route is a loop when the end of its last path, carried into map 0 through the
/// chain of switch poses, lies within closure_radius + drift × the route's length of map 0's
/// start. After a wrap the particles are spread over the drift the chain may hold (that drift as
/// two standard deviations), at least min_sigma_xy and min_sigma_theta, and the scans find the
/// robot again.
struct LoopConfig {
  bool enabled = false;
  double closure_radius = 3.0;     ///< m (route.revisit_radius)
  double drift = 0.03;             ///< odometry error per metre driven (route.online_drift)
  double min_sigma_xy = 0.1;       ///< m
  double min_sigma_theta = 0.0873;  ///< rad: the odometry's 1 % scale error over a full turn
};

/// What the map server does at a control tick (MapServer::Decide).
enum class MapStep {
  kStay,  ///< the estimate is not at the end of the current path
  kNext,  ///< at the end of a path that is not the last: switch to the next map
  kWrap,  ///< at the end of the last path of a loop with LoopConfig::enabled: back to map 0
  kDone,  ///< at the end of the last path: the route is done
  kBack,  ///< off the current path and back on the previous map's: switch back to it
};

class MapServer {
 public:
  /// The estimate counts as at the end of its path within this much arc length of it (m), or
  /// when the follower says its goal is reached.
  static constexpr double kPathEndTolerance = 0.05;
  /// Of the next map's path, this much (m) from its start also counts as where the robot can be
  /// in the current map (recovery hypotheses: the robot may be past the switch point).
  static constexpr double kNextPathReach = 20.0;
  /// Of the previous map's path, this much (m) before its end counts as where a robot that
  /// drives the route backwards comes back into it (Decide's kBack).
  static constexpr double kPreviousPathReach = 20.0;

  /// Takes the teach bundle. Throws core::ConfigError if it holds no map.
  explicit MapServer(TeachBundle bundle, const LoopConfig& loop = {});

  std::size_t index() const { return index_; }
  std::size_t size() const { return bundle_.maps.size(); }
  bool IsLast() const { return index_ + 1 == bundle_.maps.size(); }
  const PartialMap& current() const { return bundle_.maps[index_]; }
  const TeachBundle& bundle() const { return bundle_; }
  /// The route is a loop and is driven again after its last map (LoopConfig).
  bool loops() const { return loops_; }

  /// Hands map 0 and path 0 to the localizer and the follower (the start of playback).
  void Start(Localizer& localizer, PathFollower& follower);
  /// The one rule: at the end of the current path (follower goal reached, or within
  /// kPathEndTolerance of the end), the next map; after the last one, map 0 again for a loop
  /// that is driven again, else done. Off the current path (the follower's progress waits) and
  /// within `max_distance` of the last kPreviousPathReach m of the previous map's path, back to
  /// the previous map: a robot driven backwards along the route, as a recorded drive may be, is
  /// localized in the map that holds it. A robot that follows the route never meets this case.
  /// Map 0 has no previous map, even on a loop (stepping back over the loop's closure would
  /// spread the particles over the chain's drift at every pass through the start).
  MapStep Decide(const FollowerOutput& follower_output, const core::Pose2& X_MR,
                 double max_distance) const;
  /// Switches to the next map: the localizer gets map k+1 with every particle and the
  /// estimate transformed by eq. (1), the follower gets path k+1. Requires !IsLast().
  MapSwitch SwitchToNext(Localizer& localizer, PathFollower& follower);

  /// For a route driven again and again (a loop): the last map's frame in map 0's, chained
  /// through the switch poses by eq. (1), X_{M_0 M_n} = X_{M_0 S_0} * ... * X_{M_{n-1} S_{n-1}}
  /// (the identity for one map). It carries the drift the maps accumulated over the route.
  core::Pose2 LastMapInFirst() const;
  /// From the end of the last path back to map 0 and path 0 (the loop driven again): every
  /// particle becomes X_{M_0 R} = LastMapInFirst() * X_{M_n R}, then the particles are spread
  /// as LoopConfig says. Requires IsLast().
  MapSwitch WrapToFirst(Localizer& localizer, PathFollower& follower);
  /// Back to the previous map (Decide's kBack): every particle becomes
  /// X_{M_{k-1} R} = X_{M_{k-1} S} * X_{M_k R} (eq. (1) inverted); the follower's progress
  /// starts where the robot is on the previous path's end. Requires index() > 0.
  MapSwitch SwitchBack(Localizer& localizer, PathFollower& follower);

 private:
  // The current path's poses and the first kNextPathReach m of the next map's (in the current
  // map's frame): where recovery looks for the robot.
  void HandOver(Localizer& localizer, PathFollower& follower);
  void SpreadAfterWrap(Localizer& localizer) const;

  TeachBundle bundle_;
  LoopConfig loop_;
  bool loops_ = false;
  double route_length_ = 0.0;
  std::size_t index_ = 0;
  // The previous map's path's last kPreviousPathReach m, in the current map's frame.
  std::vector<core::Vec2> previous_tail_;
  std::vector<double> previous_tail_arc_;
};

}  // namespace retrace::nav
