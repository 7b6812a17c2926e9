#pragma once
// Ground truth expressed in a partial map. A partial map's frame M_k is the teaching run's
// odometry frame at the moment the map started, so it drifts against the world W: the truth
// "where the robot is in M_k" only exists locally, relative to the teaching run. For a robot
// at X_WR near teaching sample j of map k, the local truth is
//
//   X_{M_k R} = X_{M_k R_j} * inverse(X_{W R_j}) * X_{W R}            (docs/DESIGN.md §6)
//
// with j the teaching sample of the map where the robot projects onto the segment's path,
// tracked along it: the projection (core/path_projection.hpp) is searched within `window` m of
// arc length behind and ahead of the previous match, so that a segment that passes the same
// place twice (mode `single`) matches the right pass, and j is the nearer end of the piece of
// path it falls on; only when the path is farther than `fallback_distance` from the robot
// there is the nearest sample of the whole segment taken, if it is nearer. The windowed
// projection is answered by a core::PathIndex within fallback_distance: the same projection,
// from the few segments near the robot instead of every one in the window.

#include <cstddef>
#include <memory>
#include <vector>

#include "bench/engine/trace.hpp"
#include "core/path_index.hpp"
#include "core/pose2.hpp"

namespace retrace::bench {

class LocalTruth {
 public:
  /// `map` must outlive this object and hold at least one sample (checked).
  LocalTruth(const TeachMapTrace& map, double window, double fallback_distance);

  /// The local truth X_{M_k R} for the ground truth X_WR; moves the match along.
  core::Pose2 InMap(const core::Pose2& X_WR);
  /// Starts the tracking again at the map's first sample (the robot entered the map).
  void Reset() { match_ = 0; }
  /// Index of the teaching sample matched by the last InMap.
  std::size_t match() const { return match_; }
  /// The local alignment of the last match, X_{W M_k} = X_{W R_j} * inverse(X_{M_k R_j}): it
  /// carries an estimate in M_k into W (est.tum), so that comparing it with the ground truth
  /// gives exactly the localization error.
  core::Pose2 X_WM() const { return map_->X_WR[match_] * map_->X_MR[match_].Inverse(); }

 private:
  std::size_t Nearest(const core::Vec2& p, std::size_t lo, std::size_t hi, double* d2) const;

  // The teaching samples' positions (W), their arc length along the segment and the windowed
  // projection over them within fallback_distance; shared by copies (the index refers to the
  // vectors it sits beside, so it never moves).
  struct Path {
    Path(std::vector<core::Vec2> points, double radius);
    Path(const Path&) = delete;
    Path& operator=(const Path&) = delete;
    std::vector<core::Vec2> positions;
    std::vector<double> arc;
    core::PathIndex index;
  };

  const TeachMapTrace* map_;
  double window_;
  double fallback_distance_;
  std::shared_ptr<const Path> path_;
  std::size_t match_ = 0;
};

/// The local truth across map switches, for playback and log replay alike: a LocalTruth of the
/// current map's teaching trace, whose match starts again at the beginning of every map entered.
class LocalTruthAcrossMaps {
 public:
  /// Starts in map 0. `teach` must outlive this object and hold a trace of every map entered
  /// (checked when entered).
  LocalTruthAcrossMaps(const TeachTrace& teach, double window, double fallback_distance);
  /// The robot entered map `map` (a switch, or map 0 again after a loop's last map).
  void Enter(std::size_t map);
  /// The map whose teaching samples pass nearest the ground truth X_WR, a sample driven across
  /// the truth's heading counting up to 1 m farther (the first of equals): where a run that
  /// begins mid-route begins.
  std::size_t NearestMap(const core::Pose2& X_WR) const;
  /// The local truth X_{M_k R} in the current map for the ground truth X_WR.
  core::Pose2 InMap(const core::Pose2& X_WR) { return current_.InMap(X_WR); }
  const LocalTruth& current() const { return current_; }

 private:
  const TeachTrace& teach_;
  double window_;
  double fallback_distance_;
  LocalTruth current_;
};

/// Position (m) and heading (rad, absolute) error of an estimate against a truth.
struct PoseError {
  double distance = 0.0;
  double angle = 0.0;
};
PoseError Compare(const core::Pose2& estimate, const core::Pose2& truth);

}  // namespace retrace::bench
