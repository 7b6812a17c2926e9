#pragma once
// How well a mode's maps were cut, judged on the teaching drive's ground truth — the check that
// online switching (nav/online_switcher.hpp), which never sees the route, did its job:
//   maps        partial maps made
//   minimum     the fewest maps this drive needs so that none holds a place twice after a loop
//               longer than the drift rule allows: greedy cuts just before each such revisit
//               (SuggestSwitchPoints on the driven path), which is optimal because a piece of a
//               map without one has none either
//   revisiting  maps that hold a place twice after such a loop: their stretch of the driven path
//               comes within route.revisit_radius of an earlier part of the same stretch lying
//               more than 3·revisit_radius and more than route.revisit_tolerance /
//               route.online_drift behind (CheckSwitchPoints on the driven path); must be 0. A
//               shorter loop (a dead end turned back from) gathers less drift than the localizer
//               tolerates and is no fault.
// The driven path is the ground-truth trajectory of the teaching drive, and switches are placed
// on it at the distance driven when each map began. Each switch also says why it happened:
//   operator      a listed switch point (route.switch_points: [...])
//   auto          a point planned from the route (route.switch_points: auto)
//   revisit       online switching, before the robot came back to the map's trail
//   drift_budget  online switching, the map had been driven for its drift budget
//                 (route.online_drift_budget)

#include <string>
#include <vector>

#include "bench/engine/scenario.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/engine/trace.hpp"

namespace retrace::bench {

/// How many switches happened for each reason (see above).
struct SwitchReasonCounts {
  int operator_points = 0;
  int auto_points = 0;
  int revisit = 0;
  int drift_budget = 0;
};

struct SwitchingQuality {
  int maps = 0;
  int minimum = 0;
  int revisiting = 0;
  std::vector<double> switch_travel_m;  ///< m driven (ground truth) when map k+1 began
  std::vector<std::string> reasons;     ///< why, one per switch_travel_m (empty: not known)
  SwitchReasonCounts reason_counts;     ///< of `reasons`
  std::vector<std::string> warnings;    ///< one per revisiting map, naming where
};

/// Why each map after the first began, in order: "revisit" or "drift_budget" from the online
/// recorder's switches, "auto" for points planned from the route, "operator" for listed points.
/// Empty for a mode that does not switch maps.
std::vector<std::string> SwitchReasons(const ModeTeach& teach, const RouteConfig& route);

/// The switching quality of one mode's teach trace (see above); `reasons` (SwitchReasons), if
/// given, says why map k + 1 began at [k]; min_loop (m) is the drift rule's shortest loop that
/// counts (nav::OnlineSwitchingConfig::MinMapLength). Throws core::ConfigError for a
/// revisit_radius that is not > 0.
SwitchingQuality EvaluateSwitching(const TeachTrace& trace, double revisit_radius,
                                   const std::vector<std::string>& reasons = {},
                                   double min_loop = 0.0);

}  // namespace retrace::bench
