#pragma once
// The map server of the playback phase (paper §4.3): it holds the sequence of partial maps and
// taught paths, and at the end of path k hands map k+1 and path k+1 to the localizer and the
// path follower, transforming the estimate and every particle by the paper's eq. (1).

#include <cstddef>

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

class MapServer {
 public:
  /// Takes the teach bundle. Throws core::ConfigError if it holds no map.
  explicit MapServer(TeachBundle bundle);

  std::size_t index() const { return index_; }
  std::size_t size() const { return bundle_.maps.size(); }
  bool IsLast() const { return index_ + 1 == bundle_.maps.size(); }
  const PartialMap& current() const { return bundle_.maps[index_]; }
  const TeachBundle& bundle() const { return bundle_; }

  /// Hands map 0 and path 0 to the localizer and the follower (the start of playback).
  void Start(Localizer& localizer, PathFollower& follower);
  /// True when the follower has reached the end of the current path and a next map exists:
  /// the robot has stopped at the switch point and the switch is due.
  bool SwitchDue(const FollowerOutput& follower_output) const {
    return follower_output.goal_reached && !IsLast();
  }
  /// Switches to the next map: the localizer gets map k+1 with every particle and the
  /// estimate transformed by eq. (1), the follower gets path k+1. Requires !IsLast().
  MapSwitch SwitchToNext(Localizer& localizer, PathFollower& follower);

  /// For a route driven again and again (a loop): the last map's frame in map 0's, chained
  /// through the switch poses by eq. (1), X_{M_0 M_n} = X_{M_0 S_0} * ... * X_{M_{n-1} S_{n-1}}
  /// (the identity for one map). It carries the drift the maps accumulated over the route.
  core::Pose2 LastMapInFirst() const;
  /// From the end of the last path back to map 0 and path 0 (the loop driven again): every
  /// particle becomes X_{M_0 R} = LastMapInFirst() * X_{M_n R}. Requires IsLast().
  MapSwitch WrapToFirst(Localizer& localizer, PathFollower& follower);

 private:
  TeachBundle bundle_;
  std::size_t index_ = 0;
};

}  // namespace retrace::nav
