#pragma once
// Layers several figures share, drawn on a GL canvas (private to viz).

#include <string>
#include <vector>

#include "viz/figure_data.hpp"
#include "viz/gl_canvas.hpp"
#include "viz/internal/annotate.hpp"

namespace retrace::viz::internal {

/// Marker sizes (output px) used in every figure.
inline constexpr double kStartMarkerPx = 15.0;
inline constexpr double kSwitchMarkerPx = 17.0;

/// The static geometry in light grey, skipping what lies outside the canvas's view.
void DrawWorld(GlCanvas& canvas, const WorldShapes& world);
/// The start marker: a white disc with a black outline.
void DrawStart(GlCanvas& canvas, const Vec2& p);
/// Map-switch markers: gold diamonds with a black outline.
void DrawSwitches(GlCanvas& canvas, const std::vector<Vec2>& points);

/// Legend entries for the start and switch markers and the world geometry.
LegendEntry StartLegend();
LegendEntry SwitchLegend();
LegendEntry WorldLegend();

/// Index ranges [begin, end) of `route` between consecutive switch points: split k ends where
/// the route first passes closest to switch k (its first visit within 1 m, else the nearest
/// point after the previous split). Returns switch count + 1 ranges.
std::vector<std::pair<std::size_t, std::size_t>> SplitAtSwitches(const std::vector<core::Pose2>& route,
                                                                 const std::vector<core::Pose2>& switches);

/// What a world-frame panel shows around `content` (trajectories, markers): the content with
/// a margin of a tenth of its size (1..10 m), grown to the whole world when the world is not
/// much larger, so that a small room is shown whole and a campus is cropped to the route.
Box2 WorldViewBox(const Box2& content, const WorldShapes& world);

/// The length of the polyline through the poses' positions (m).
double PathLength(const std::vector<core::Pose2>& poses);

/// The box around the cells of `grid` that were ever observed (log-odds != 0), carried by X_WM;
/// empty when none were.
Box2 KnownCellsBox(const core::OccupancyGrid& grid, const core::Pose2& X_WM = {});
/// The same for the occupied cells (probability >= 0.65): the map's structure, without the
/// free rays that reach past it.
Box2 OccupiedCellsBox(const core::OccupancyGrid& grid, const core::Pose2& X_WM = {});

}  // namespace retrace::viz::internal
