#pragma once
// Where a map switch is safe to make (the paper's §3.1: switch "at places with enough landmarks
// ahead"): after a switch the localizer starts in the new map from the transformed pose, and a
// scan that does not pin the pose down — a featureless corridor along its axis, an open field —
// lets that start drift before the map has anything to hold on to. So a switch point's place is
// judged by how well a scan taken there constrains the robot's position (nav/scan_constraint.hpp).

#include <string>
#include <vector>

#include "bench/engine/scenario.hpp"

namespace retrace::bench {

/// A switch point's place and the best place near it.
struct SwitchPlace {
  double s = 0.0;                ///< arc length (m) of the switch point
  double constraint = 0.0;       ///< of a scan taken there, facing along the route
  double best_s = 0.0;           ///< the best place within `window` m before it (may be s)
  double best_constraint = 0.0;  ///< of a scan taken there
};

/// Simulates a scan (the scenario's LiDAR, in its teach world, without pedestrians, facing along
/// the route) at each switch point and every 0.5 m up to `window` m before it (never before the
/// previous switch point), and returns where each could best be.
std::vector<SwitchPlace> JudgeSwitchPlaces(const Scenario& scenario,
                                           const std::vector<double>& switch_points, double window);

/// A warning for each switch point whose scan constrains the pose by less than `minimum`,
/// naming its arc length and the better place nearby if there is one.
std::vector<std::string> SwitchPlaceWarnings(const std::vector<SwitchPlace>& places,
                                             double minimum);

}  // namespace retrace::bench
