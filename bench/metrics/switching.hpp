#pragma once
// How well a mode's maps were cut, judged on the teaching drive's ground truth — the check that
// online switching (nav/online_switcher.hpp), which never sees the route, did its job:
//   maps        partial maps made
//   minimum     the fewest maps this drive needs so that none holds a place twice: greedy cuts
//               just before each revisit (SuggestSwitchPoints on the driven path), which is
//               optimal because a piece of a map that holds no place twice holds none either
//   revisiting  maps that hold a place twice: their stretch of the driven path comes within
//               route.revisit_radius of an earlier part of the same stretch lying more than
//               3·revisit_radius behind (CheckSwitchPoints on the driven path); must be 0
// The driven path is the ground-truth trajectory of the teaching drive, and switches are placed
// on it at the distance driven when each map began.

#include <string>
#include <vector>

#include "bench/engine/trace.hpp"

namespace retrace::bench {

struct SwitchingQuality {
  int maps = 0;
  int minimum = 0;
  int revisiting = 0;
  std::vector<double> switch_travel_m;  ///< m driven (ground truth) when map k+1 began
  std::vector<std::string> warnings;    ///< one per revisiting map, naming where
};

/// The switching quality of one mode's teach trace (see above). Throws core::ConfigError for a
/// revisit_radius that is not > 0.
SwitchingQuality EvaluateSwitching(const TeachTrace& trace, double revisit_radius);

}  // namespace retrace::bench
