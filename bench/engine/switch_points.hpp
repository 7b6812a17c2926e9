#pragma once
// Where a scenario's partial maps start: map-switch points are arc lengths (m) along the route
// (a polyline in W). Teaching starts a fresh partial map at each of them, so that no partial
// map has to hold the same place twice: odometry drift would draw it twice, offset, and the
// localizer would then match the wrong copy (docs/DESIGN.md §5, the paper's reason for partial
// maps). Map k covers the route from switch point k-1 (or the start) to switch point k (or the
// end).

#include <string>
#include <vector>

#include "core/pose2.hpp"

namespace retrace::bench {

/// The pose on the route at arc length s (clamped to the route), facing along its segment;
/// `cum` is core::CumulativeArcLength(route) (at least 2 points).
core::Pose2 RoutePoseAt(const std::vector<core::Vec2>& route, const std::vector<double>& cum,
                        double s);

/// "123.4 m": an arc length rounded to 0.1 m, for messages.
std::string ArcLengthText(double s);

/// Total length (m) of the route polyline; 0 for fewer than 2 points.
double RouteLength(const std::vector<core::Vec2>& route);

/// Checks that no partial map revisits its own area: a point of map k's stretch of route that
/// comes within `revisit_radius` (m) of an earlier part of the same stretch lying more than
/// 3·revisit_radius of arc length behind it means the switch to map k+1 comes too late.
/// Returns one human-readable warning per such map (naming the map index and the arc length
/// where the revisit starts), or nothing when every map is fine.
/// Throws core::ConfigError("route.switch_points", ...) for switch points that are not
/// strictly increasing, ≤ 0 or ≥ the route length (the message gives the length), and
/// core::ConfigError for a route of fewer than 2 points or a revisit_radius that is not > 0.
/// With min_loop > 0 only a revisit after more than min_loop m of travel counts: a shorter loop
/// gathers less drift than the localizer tolerates (route.revisit_tolerance / online_drift,
/// nav::OnlineSwitchingConfig::MinMapLength).
std::vector<std::string> CheckSwitchPoints(const std::vector<core::Vec2>& route,
                                           const std::vector<double>& switch_points,
                                           double revisit_radius, double min_loop = 0.0);

/// Greedy switch points (m of arc length): each new map starts just before the current one
/// would begin to revisit itself, in the sense of CheckSwitchPoints, which finds no fault in
/// the result. Empty when the route never revisits itself. Throws like CheckSwitchPoints.
std::vector<double> SuggestSwitchPoints(const std::vector<core::Vec2>& route,
                                        double revisit_radius, double min_loop = 0.0);

}  // namespace retrace::bench
