#pragma once
// The navigation stack as the playback loop sees it (docs/DESIGN.md §6, "The stack interface"):
// odometry, scans and time in; the command, the estimate, the map it is in and whether it deems
// itself lost out. retrace's navigator with obstacle avoidance is one implementation
// (bench/engine/retrace_stack.hpp), replaying the taught path on odometry alone another
// (bench/engine/odometry_stack.hpp), and a stack stepped from outside (Python) a third. The
// loop never reaches past this interface into a stack, except to let the video and the update
// scoring look at retrace's own navigator when that is the stack (navigator()).

#include <cstddef>
#include <optional>

#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "core/twist.hpp"
#include "nav/localizer.hpp"
#include "nav/map_server.hpp"
#include "nav/navigator.hpp"
#include "nav/obstacle_avoidance.hpp"

namespace retrace::bench {

/// What a stack answers at a control tick.
struct StackOutput {
  /// The command to send (after the stack's own obstacle avoidance, if it has one; `modified`,
  /// `blocked` and `emergency_stop` count in the metrics).
  nav::AvoidanceOutput drive;
  /// The estimate X_MR in map `map`'s frame: the taught maps' frames (map k starts at the
  /// teaching drive's odometry pose where it began). Scored against the local truth there.
  core::Pose2 X_MR;
  std::size_t map = 0;
  bool lost = false;        ///< the stack deems itself lost
  bool off_map = false;     ///< no map covers its place: it runs on odometry alone
  bool route_done = false;  ///< it reached the end of the route
  bool last_map = false;    ///< map is the route's last
  double remaining = 0.0;   ///< m of its current path left (the end conditions' progress)
  std::optional<nav::MapSwitch> map_switch;  ///< the map switch it made at this tick
};

class NavigationStack {
 public:
  virtual ~NavigationStack() = default;
  /// One odometry increment (robot frame) at time t (s since the run started).
  virtual void OnOdometry(double t, const core::OdometryDelta& delta) = 0;
  /// One scan (LiDAR frame, stamped). A stack built on retrace's localizer returns the update
  /// it ran, so that its dynamic-point rejection is scored; others return nullptr.
  virtual const nav::LocalizerUpdate* OnScan(const core::LaserScan& scan) = 0;
  /// One control tick at time t, dt s after the previous one.
  virtual StackOutput OnControlTick(double t, double dt) = 0;
  /// An operator drove the robot and hands it back at the tick whose answer is *out: where is
  /// it on the route now? Updates out's estimate, map and lost flag; returns the map switch when
  /// the map changed. By default the stack carries on as it was.
  virtual std::optional<nav::MapSwitch> Resume(StackOutput* out) {
    (void)out;
    return std::nullopt;
  }
  /// retrace's navigator when it is the stack (the video and the scan snapshot look into it),
  /// else nullptr.
  virtual const nav::Navigator* navigator() const { return nullptr; }
};

}  // namespace retrace::bench
