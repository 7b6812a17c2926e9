#pragma once
// The teaching drive: the simulated operator drives the route once while teach recorders build
// the maps of every requested mode from the same sensor data — so that the modes differ only
// in how the maps were made (docs/DESIGN.md §6):
//   partial     odometry poses, a new map at every switch point (the paper's method)
//   single      odometry poses, one map
//   consistent  ground-truth poses relative to the start, one map (a perfect SLAM's map)
//   scan_matched  odometry poses corrected by scan-to-map matching at every keyframe, a new
//               map at every switch point (the paper's §5.4 remedy)

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "bench/engine/progress.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/sensor_tap.hpp"
#include "bench/engine/trace.hpp"
#include "nav/teach_bundle.hpp"
#include "nav/teach_recorder.hpp"
#include "sim/collision_event.hpp"

namespace retrace::bench {

struct ModeTeach {
  MapMode mode = MapMode::kPartial;
  nav::TeachBundle bundle;
  TeachTrace trace;  ///< the drive's ground truth, with this mode's per-map references
  /// scan_matched: keyframe matches by verdict (nav::MatchVerdict order); zero otherwise
  std::array<int, 5> match_counts{};
  /// route.switch_points: online — the switches the recorder made, in order
  std::vector<nav::OnlineSwitch> online_switches;
};

struct TeachResult {
  double duration_s = 0.0;  ///< simulated
  double cpu_time_s = 0.0;  ///< the drive's thread and its recorders' helper threads
  std::vector<sim::CollisionEvent> collisions;
  std::vector<std::string> events;  ///< "time name" of each scripted event fired
  std::vector<ModeTeach> modes;     ///< in the order requested
};

/// Throws core::ConfigError("route.switch_points", ...) when switching is `online` but none of
/// `modes` switches maps (a consistent or single map alone).
void RequireSwitchingModeIfOnline(const Scenario& scenario, const std::vector<MapMode>& modes);

/// One map mode's teach recorder, fed from a drive (the simulator's or a log's).
struct ModeRecorder {
  MapMode mode = MapMode::kPartial;
  nav::TeachRecorder recorder;
  std::size_t next_switch = 0;  ///< the next listed switch point to signal
};

/// The recorders of `modes` for one drive: scan matching for scan_matched, `online` switching
/// (if given) for the modes that switch maps.
std::vector<ModeRecorder> MakeModeRecorders(
    const std::vector<MapMode>& modes, const NavConfig& nav, const nav::RobotGeometry& robot,
    const std::optional<nav::OnlineSwitchingConfig>& online);

/// The operator's switch signal: closes the map of every recorder that switches maps once per
/// switch point (m, increasing) that `progress` (m) has reached.
void SignalSwitches(std::vector<ModeRecorder>& recorders, const std::vector<double>& switch_points,
                    double progress);

/// Finishes every recorder into its mode's teach: the bundle, and the drive's `trace` with the
/// per-map traces — the poses the recorder was given, at the instants `time`, beside the truth
/// `X_WR` (one entry per OnPose call, in order; `X_WR` may be empty: no truth). Each bundle's
/// revisits are found and registered with the route's drift and revisit radius (nav::LinkRoute).
std::vector<ModeTeach> FinishModeRecorders(std::vector<ModeRecorder>& recorders,
                                           const TeachTrace& trace, const std::vector<double>& time,
                                           const std::vector<core::Pose2>& X_WR,
                                           const RouteConfig& route);

/// Drives the route with the teacher and builds the bundles of `modes`; `tap` (optional) gets
/// a copy of the sensor stream. With `threads` > 1, the recorders of the modes are shared out
/// over up to `threads` threads (the drive's own and helpers), each recorder on one of them,
/// while the drive's thread simulates on; the bundles do not depend on `threads`. Throws like
/// RequireSwitchingModeIfOnline, and
/// core::WorldError when the teacher does not finish the route within the teach timeout (a
/// route it cannot drive), with where it got stuck.
TeachResult RunTeachDrive(const Scenario& scenario, const std::vector<MapMode>& modes,
                          const ProgressFn& progress = {}, SensorTap* tap = nullptr,
                          int threads = 1);

}  // namespace retrace::bench
