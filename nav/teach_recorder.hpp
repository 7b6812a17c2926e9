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
//
// With online switching (nav/online_switcher.hpp) there is no operator: the recorder switches by
// itself just before the robot comes back to where the current map has been, or when the map
// has been driven for its drift budget, at the place of the last `window` metres whose scan
// constrains the pose best. To choose a place behind the
// robot it holds the latest poses and scans back and builds its maps that far behind the robot;
// Finish() builds the rest. Scans taken at exactly the pose of the scan before them (the robot
// standing still) are dropped from that buffer: the mapper would not integrate them either.

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <variant>
#include <vector>

#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "nav/mapper.hpp"
#include "nav/online_switcher.hpp"
#include "nav/scan_matcher.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::nav {

/// Where the recorder put one pose it was given: the map and the pose in that map's frame.
struct RecordedPose {
  std::uint32_t map = 0;  ///< index k of the map
  core::Pose2 X_MR;       ///< X_{M_k R}
};

/// A switch the recorder made by itself (online switching).
struct OnlineSwitch {
  double travelled = 0.0;   ///< m the source's poses had travelled at the switch
  double constraint = 0.0;  ///< of the scan at the switch place (nav/scan_constraint.hpp)
  /// kRevisit: the robot was coming back to the map's trail; kDriftBudget: the map had been
  /// driven for its drift budget (OnlineSwitchingConfig::MaxMapLength()).
  SwitchReason reason = SwitchReason::kRevisit;
};

/// Builds the partial maps of one teaching drive.
class TeachRecorder {
 public:
  /// Starts map 0 for the robot `robot`; with `matcher`, keyframe poses are corrected by scan
  /// matching; with `online`, the recorder switches maps by itself. Throws core::ConfigError for
  /// an invalid mapper, matcher or switching config or geometry.
  TeachRecorder(const MapperConfig& config, const RobotGeometry& robot,
                const std::optional<ScanMatcherConfig>& matcher = std::nullopt,
                const std::optional<OnlineSwitchingConfig>& online = std::nullopt);

  /// The robot's pose X_OR (m, rad) in the pose source's frame O, at each odometry tick.
  void OnPose(const core::Pose2& X_OR);

  /// A scan taken at the latest pose; integrated into the current map if a keyframe is due.
  /// Scans before the first pose are ignored. Returns whether the scan was integrated now
  /// (always false with online switching, whose maps are built behind the robot).
  bool OnScan(const core::LaserScan& scan);

  /// The operator's switch signal: closes the current map k — its grid, its path and its
  /// switch pose X_{M_k S} (the current pose in M_k) — and starts map k+1 at the current
  /// pose, which becomes its identity. The path is the keyframe poses in M_k, preceded by the
  /// identity (the map's start) and followed by X_{M_k S} where they are not already so.
  /// Not with online switching.
  void CloseMap();

  /// Builds what is still held back, closes the last map and returns all of them, in order. The
  /// recorder must not be used afterwards, except for the accessors below.
  TeachBundle Finish();

  /// Index k of the map being built.
  std::size_t map_index() const { return closed_.size(); }
  /// The pose X_{M_k R} in the map being built (with online switching: of the latest pose
  /// built into it, which lags behind the robot).
  const core::Pose2& pose() const { return mapper_.pose(); }
  /// The mapper of the map being built.
  const Mapper& mapper() const { return mapper_; }
  /// The maps closed so far.
  const std::vector<PartialMap>& closed_maps() const { return closed_; }
  /// How many keyframe matches ended with each verdict, indexed by MatchVerdict (all zero
  /// without a matcher).
  const std::array<int, 5>& match_counts() const { return match_counts_; }
  /// One entry per OnPose call built into a map so far, in order (all of them after Finish()).
  const std::vector<RecordedPose>& recorded_poses() const { return recorded_; }
  /// The switches made by online switching, in order.
  const std::vector<OnlineSwitch>& online_switches() const { return switches_; }

 private:
  struct Held {
    std::variant<core::Pose2, core::LaserScan> event;  ///< a pose X_OR or a scan
    double travelled = 0.0;                            ///< m, when it came
  };

  void ApplyPose(const core::Pose2& X_OR);
  bool ApplyScan(const core::LaserScan& scan);
  void StartNextMap();
  void SwitchOnline(SwitchReason reason);
  void BuildFirstHeld();
  void BuildHeldUpTo(double travelled);

  MapperConfig config_;
  RobotGeometry robot_;
  Mapper mapper_;
  std::optional<core::Pose2> X_OM_;  // origin of the current map in O, once known
  std::optional<core::Pose2> X_OR_;  // latest source pose built into the map
  std::optional<ScanMatcher> matcher_;
  core::Pose2 X_MK_;                 // with a matcher: the last corrected keyframe pose in M ...
  std::optional<core::Pose2> X_OK_;  // ... and the source pose at that keyframe
  std::array<int, 5> match_counts_{};
  std::vector<PartialMap> closed_;
  std::vector<RecordedPose> recorded_;
  bool finished_ = false;

  // Online switching.
  std::optional<RevisitDetector> detector_;
  std::deque<Held> held_;
  std::optional<core::Pose2> X_OR_latest_;     // the latest pose given
  std::optional<core::Pose2> X_OR_last_scan_;  // the pose of the latest scan held
  double map_start_travelled_ = 0.0;           // m, where the current map began
  std::vector<OnlineSwitch> switches_;
};

}  // namespace retrace::nav
