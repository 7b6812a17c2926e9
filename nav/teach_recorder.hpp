#pragma once
// The teach recorder (docs/DESIGN.md §5): runs the mapper during the teaching drive and, on the
// operator's switch signal, closes the current partial map and starts the next one at the
// identity. It takes the robot's pose from whatever source the caller uses — integrated
// odometry for the `partial` and `single` map modes, ground truth for `consistent` — as an
// absolute pose X_OR in that source's frame O.
//
// Map k's frame M_k is the source pose at the moment map k was started (the first pose of the
// drive for map 0, the pose at the previous switch otherwise), so
//   X_{M_k R} = inverse(X_{O M_k}) * X_OR,
// and map k's switch pose X_{M_k S} is X_{M_k R} at the switch; then
// X_{M_{k+1} R} = inverse(X_{M_k S}) * X_{M_k R} (paper eq. 1) holds by construction.
//
// With a scan matcher (the `scan_matched` map mode) each keyframe's scan is first aligned with
// the map being built (nav/scan_matcher.hpp, which keeps the map's surface points next to its
// grid) and the map takes the corrected pose; between
// keyframes the pose is the last corrected keyframe pose moved by the odometry since:
//   X_{M_k R} = X_{M_k K} * inverse(X_{O K}) * X_OR.
// A refused match keeps the odometry prediction for that keyframe. The switch pose and eq. (1)
// then hold for the corrected poses.

#include <array>
#include <optional>
#include <vector>

#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "nav/mapper.hpp"
#include "nav/scan_matcher.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::nav {

/// Builds the partial maps of one teaching drive.
class TeachRecorder {
 public:
  /// Starts map 0 for the robot `robot`; with `matcher`, keyframe poses are corrected by scan
  /// matching. Throws core::ConfigError for an invalid mapper or matcher config or geometry.
  TeachRecorder(const MapperConfig& config, const RobotGeometry& robot,
                const std::optional<ScanMatcherConfig>& matcher = std::nullopt);

  /// The robot's pose X_OR (m, rad) in the pose source's frame O, at each odometry tick.
  void OnPose(const core::Pose2& X_OR);

  /// A scan taken at the latest pose; integrated into the current map if a keyframe is due.
  /// Scans before the first pose are ignored. Returns whether the scan was integrated.
  bool OnScan(const core::LaserScan& scan);

  /// The operator's switch signal: closes the current map k — its grid, its path and its
  /// switch pose X_{M_k S} (the current pose in M_k) — and starts map k+1 at the current
  /// pose, which becomes its identity. The path is the keyframe poses in M_k, preceded by the
  /// identity (the map's start) and followed by X_{M_k S} where they are not already so.
  void CloseMap();

  /// Closes the last map and returns all of them, in order. The recorder must not be used
  /// afterwards.
  TeachBundle Finish();

  /// Index k of the map being built.
  std::size_t map_index() const { return closed_.size(); }
  /// The current pose X_{M_k R} in the map being built.
  const core::Pose2& pose() const { return mapper_.pose(); }
  /// The mapper of the map being built.
  const Mapper& mapper() const { return mapper_; }
  /// The maps closed so far.
  const std::vector<PartialMap>& closed_maps() const { return closed_; }
  /// How many keyframe matches ended with each verdict, indexed by MatchVerdict (all zero
  /// without a matcher).
  const std::array<int, 5>& match_counts() const { return match_counts_; }

 private:
  MapperConfig config_;
  RobotGeometry robot_;
  Mapper mapper_;
  std::optional<core::Pose2> X_OM_;  // origin of the current map in O, once known
  std::optional<core::Pose2> X_OR_;  // latest source pose
  std::optional<ScanMatcher> matcher_;
  core::Pose2 X_MK_;                 // with a matcher: the last corrected keyframe pose in M ...
  std::optional<core::Pose2> X_OK_;  // ... and the source pose at that keyframe
  std::array<int, 5> match_counts_{};
  std::vector<PartialMap> closed_;
  bool finished_ = false;
};

}  // namespace retrace::nav
