#pragma once
// Ground truth expressed in a partial map. A partial map's frame M_k is the teaching run's
// odometry frame at the moment the map started, so it drifts against the world W: the truth
// "where the robot is in M_k" only exists locally, relative to the teaching run. For a robot
// at X_WR near teaching sample j of map k, the local truth is
//
//   X_{M_k R} = X_{M_k R_j} * inverse(X_{W R_j}) * X_{W R}            (DESIGN §6)
//
// with j the nearest teaching sample of the map, tracked monotonically along the segment so
// that a segment that passes the same place twice (mode `single`) matches the right pass.

#include <cstddef>

#include "bench/trace.hpp"
#include "core/pose2.hpp"

namespace retrace::bench {

class LocalTruth {
 public:
  /// `map` must outlive this object and hold at least one sample.
  explicit LocalTruth(const TeachMapTrace& map);

  /// The local truth X_{M_k R} for the ground truth X_WR; moves the match forward (or back,
  /// within the window) from the previous call's.
  core::Pose2 InMap(const core::Pose2& X_WR);
  /// Index of the teaching sample matched by the last InMap.
  std::size_t match() const { return match_; }
  /// The local alignment of the last match, X_{W M_k} = X_{W R_j} * inverse(X_{M_k R_j}): it
  /// carries an estimate in M_k into W (est.tum), so that comparing it with the ground truth
  /// gives exactly the localization error.
  core::Pose2 X_WM() const { return map_.X_WR[match_] * map_.X_MR[match_].Inverse(); }

  /// m of teaching path searched behind and ahead of the previous match.
  static constexpr double kWindow = 10.0;
  /// m: a windowed match farther than this from the robot falls back to a global search.
  static constexpr double kFallbackDistance = 3.0;

 private:
  const TeachMapTrace& map_;
  std::vector<double> arc_;  // arc length of each sample's position along the map's segment
  std::size_t match_ = 0;
};

/// Position (m) and heading (rad, absolute) error of an estimate against the local truth.
struct PoseError {
  double distance = 0.0;
  double angle = 0.0;
};
PoseError Compare(const core::Pose2& estimate, const core::Pose2& truth);

}  // namespace retrace::bench
