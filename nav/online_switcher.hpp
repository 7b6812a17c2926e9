#pragma once
// Online map switching (beyond the paper, which has the operator switch by hand, §3.1): the teach
// recorder decides by itself, while it teaches, to start a new partial map just before the robot
// comes back to a place the current map already holds — from its own odometry and scans only, no
// route and no ground truth, so it works the same in the simulator and on a recorded log.
//
// When: a revisit is what CheckSwitchPoints (bench/engine/switch_points.hpp) calls one, seen on
// the pose source's own trail instead of the route: the robot comes within revisit_radius of a
// part of the current map's trail that lies more than 3·revisit_radius of travel behind. Odometry
// drifts, so the trail bends away from where the robot really was; the radius therefore grows by
// `drift` times the distance driven between the two visits (odometry's error is a few per cent of
// the distance driven), which makes the test err on the early side.
//
// Only a revisit that is inconsistent needs a new map ("a revisit needs a new map only when it is
// inconsistent", docs/METHOD.md): what blurs a map is the drift gathered between the two visits
// of a place, not the visit. The odometry model's expected error over the loop is `drift` times
// the distance driven between the two visits; while it is at most `tolerance` (what the localizer
// tolerates in one map) the revisit is consistent and the map goes on (a U-turn after ten metres
// has drifted centimetres). The test runs on at every sample, so a robot that comes back along
// its trail switches once the loop has grown inconsistent: no map ends before tolerance / drift
// metres of travel (MinMapLength) for a revisit.
//
// Also when the map's drift reaches its budget ("switching bounds drift, not only revisits";
// docs/METHOD.md, online map switching): a map is only useful while the drift its own odometry gathered is small against
// what the localizer tolerates, and a route whose first revisit comes late would otherwise be one
// map kilometres long. The drift a map may hold is modelled as `drift` times the distance driven
// since it began (the same model that widens the revisit radius); when it reaches
// `drift_budget`, i.e. after drift_budget / drift metres of travel, the map is closed.
//
// Where: like `route.switch_points: auto`, at the place within `window` metres before the revisit
// whose scan constrains the pose best (nav/scan_constraint.hpp): after a switch the localizer
// starts in the new map from the transformed pose, so that place should have landmarks in view.
// Choosing a place behind the robot needs hindsight: the recorder holds the latest
// window + 2·step metres of poses and scans back and builds its maps that far behind the robot
// (nav/teach_recorder.hpp).

#include <algorithm>
#include <vector>

#include "core/config.hpp"
#include "core/pose2.hpp"

namespace retrace::nav {

/// What counts as a revisit, for online switching and for the switch points planned or checked
/// on a route (bench/engine/switch_points.hpp) alike: the earlier pass must lie more than
/// RevisitLag(radius) of travel behind (closer parts are the road just driven, bent by a turn),
/// and the trail is sampled every RevisitSampleStep(radius) so that a revisit cannot slip
/// between two samples unnoticed by more than a fraction of the radius.
constexpr double RevisitLag(double revisit_radius) { return 3.0 * revisit_radius; }
constexpr double RevisitSampleStep(double revisit_radius) {
  return std::clamp(revisit_radius / 8.0, 0.05, 0.5);
}

struct OnlineSwitchingConfig {
  double revisit_radius = 3.0;  ///< m (route.revisit_radius)
  double window = 10.0;  ///< m before the revisit to choose the place in (route.switch_window)
  double drift = 0.03;   ///< odometry error per metre driven, a fraction (route.online_drift)
  /// m of expected drift (drift × the map's length of travel) at which a map is closed even
  /// without a revisit (route.online_drift_budget); 0: never.
  double drift_budget = 12.0;
  /// m of expected drift over a loop (drift × the distance driven between the two visits) up to
  /// which a revisit is consistent and needs no new map (route.revisit_tolerance); 0: every
  /// revisit closes the map.
  double tolerance = 0.5;

  /// m of travel after which a map reaches its drift budget: drift_budget / drift; infinite
  /// when either is 0.
  double MaxMapLength() const;
  /// m of travel a loop must have for a revisit to close the map: tolerance / drift (0 when the
  /// tolerance is 0; infinite when drift is 0 and the tolerance is not).
  double MinMapLength() const;

  /// Throws core::ConfigError naming the key: revisit_radius > 0, window >= 0, 0 <= drift <= 0.5,
  /// drift_budget >= 0, tolerance >= 0 and, when the budget applies, MaxMapLength() > window and
  /// MaxMapLength() > MinMapLength().
  void Validate() const;
};

/// Why a map was closed: the operator's signal (a listed or an `auto` switch point), or online
/// switching's own decision before a revisit or at the drift budget.
enum class SwitchReason { kOperator, kRevisit, kDriftBudget };

/// Watches the pose source's trail for the moment the robot comes back to where the current map
/// has already been (see above).
class RevisitDetector {
 public:
  /// Throws core::ConfigError for an invalid config.
  explicit RevisitDetector(const OnlineSwitchingConfig& config);

  /// The next pose X_OR of the source. Returns whether the robot, here, comes back to the current
  /// map's trail. Only every step() metres of travel is a pose tested (and kept in the trail).
  bool OnPose(const core::Pose2& X_OR);

  /// m driven so far: the sum of the distances between consecutive poses.
  double travelled() const { return travelled_; }

  /// Whether the current map, begun at the last StartMap (or the first pose), has been driven
  /// for MaxMapLength() or more: its expected drift has reached the budget.
  bool DriftBudgetReached() const;

  /// A new map starts where the robot was after `travelled` m (at most travelled()): the trail
  /// before that no longer counts.
  void StartMap(double travelled);

  /// m of travel between the poses tested.
  double step() const { return step_; }

  const OnlineSwitchingConfig& config() const { return config_; }

 private:
  struct Sample {
    core::Vec2 p;      ///< position in the source's frame
    double travelled;  ///< m driven when the robot was there
  };

  OnlineSwitchingConfig config_;
  double step_ = 0.0;
  double lag_ = 0.0;
  double travelled_ = 0.0;
  double map_start_ = 0.0;  ///< m driven when the current map began
  double max_length_ = 0.0;
  bool has_pose_ = false;
  core::Vec2 last_p_;
  std::vector<Sample> trail_;  ///< of the current map, every step_ m
};

}  // namespace retrace::nav

template <>
struct retrace::core::EnumTraits<retrace::nav::SwitchReason> {
  static constexpr std::array<std::pair<retrace::nav::SwitchReason, std::string_view>, 3> kNames{
      {{retrace::nav::SwitchReason::kOperator, "operator"},
       {retrace::nav::SwitchReason::kRevisit, "revisit"},
       {retrace::nav::SwitchReason::kDriftBudget, "drift_budget"}}};
};
