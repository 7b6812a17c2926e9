#pragma once
// The navigation stack as the playback loop sees it (docs/DESIGN.md §6, "The stack interface"),
// in core types only: odometry, scans and time go in; the command, the estimate in a taught map's
// frame, that map, whether the stack deems itself lost or off every map, and whether it has
// reached the end of the route come out. The harness works out the rest itself (the progress
// along the taught path, whether the map is the route's last). retrace's navigator
// (bench/engine/retrace_stack.hpp), the taught paths replayed on odometry
// (bench/engine/odometry_stack.hpp) and a stack written in Python are three implementations;
// bench/engine/stack_registry.hpp finds them by name (playback.stack).
//
// This library depends on core alone (scripts/check_includes.sh): a stack built outside the tree
// needs nothing else to speak to the harness.

#include <cstddef>
#include <optional>

#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "core/twist.hpp"

namespace retrace::bench {

/// The command a stack sends, and what its own obstacle avoidance (if it has one) did to it: the
/// metrics count the ticks it changed the command, stopped for an obstacle ahead, or braked hard.
struct DriveCommand {
  core::Twist command;
  bool modified = false;        ///< avoidance changed the path follower's command
  bool blocked = false;         ///< it stopped for an obstacle ahead
  bool emergency_stop = false;  ///< it stopped for an obstacle inside the stop distance
};

/// A move from one taught map into another: the estimate X_MkR in map `from` just before, and
/// X_MnR in map `to` just after (eq. (1) for a switch at a path's end).
struct MapChange {
  std::size_t from = 0;
  std::size_t to = 0;
  core::Pose2 X_MkR;
  core::Pose2 X_MnR;
};

/// What a stack answers at a control tick.
struct StackOutput {
  DriveCommand drive;
  /// The estimate X_MR in map `map`'s frame: the taught maps' frames (map k starts at the
  /// teaching drive's odometry pose where it began). Scored against the local truth there.
  core::Pose2 X_MR;
  std::size_t map = 0;
  bool lost = false;                    ///< the stack deems itself lost
  bool off_map = false;                 ///< no map covers its place: it runs on odometry alone
  bool route_done = false;              ///< it reached the end of the route
  std::optional<MapChange> map_change;  ///< the map change it made at this tick
};

/// The map changes a stack's answers imply: an answer in another map than the one before, which
/// names no map_change itself, changed maps from the answer before's estimate to its own. The
/// harness applies it to every answer that does not come from retrace's navigator.
class MapChangeTracker {
 public:
  void Apply(StackOutput* out) {
    if (!out->map_change && out->map != map_)
      out->map_change = MapChange{map_, out->map, X_MR_, out->X_MR};
    map_ = out->map;
    X_MR_ = out->X_MR;
  }

 private:
  std::size_t map_ = 0;
  core::Pose2 X_MR_;
};

/// Defined by the harness (bench/engine/stack_insight.hpp) for stacks built on retrace's
/// localizer; a stack that is not need never see it.
class StackInsight;

class NavigationStack {
 public:
  virtual ~NavigationStack() = default;
  /// One odometry increment (robot frame) at time t (s since the run started).
  virtual void OnOdometry(double t, const core::OdometryDelta& delta) = 0;
  /// One scan (LiDAR frame, stamped).
  virtual void OnScan(const core::LaserScan& scan) = 0;
  /// One control tick at time t, dt s after the previous one.
  virtual StackOutput OnControlTick(double t, double dt) = 0;
  /// An operator drove the robot and hands it back at the tick whose answer is *out: where is
  /// it on the route now? Updates out's estimate, map and lost flag; returns the map change when
  /// the map changed. By default the stack carries on as it was.
  virtual std::optional<MapChange> Resume(StackOutput* out) {
    (void)out;
    return std::nullopt;
  }
  /// Optional: what the harness may look at inside the stack to score more than the output
  /// (dynamic-point rejection, the video's particles); nullptr: nothing.
  virtual const StackInsight* insight() const { return nullptr; }
};

}  // namespace retrace::bench
