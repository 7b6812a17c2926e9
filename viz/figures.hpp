#pragma once
// The paper's figures and the harness's summaries, one function per figure, each writing a PNG
// atomically and returning where its panels sit so that callers (and tests) can find the pixel
// of a world point. Rendering uses OSMesa for the world-space layers and OpenCV for text, axes
// and plots; it is deterministic (same data, same binary: same bytes) and uses no clock.
//
// Every function throws RenderError when no off-screen context can be made (nothing is
// written) and core::IoError when the file cannot be written; data the figure needs but lacks
// (no maps, no runs) gives core::IoError naming the figure.
//
// Colours follow viz/style.hpp in every figure; text is Hershey Duplex sized for 100% zoom.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "viz/figure_data.hpp"
#include "viz/view.hpp"

namespace retrace::viz {

struct FigureOptions {
  int width = 1600;     ///< px of the whole figure, 400..8000
  int supersample = 2;  ///< 1..4, anti-aliasing of the world-space layers
  std::string title;    ///< empty: the figure's default title

  /// Throws core::ConfigError naming `width` or `supersample` when out of range (or when
  /// width x supersample exceeds what OSMesa renders). Every Render*Figure calls it first.
  void Validate() const;
};

/// Where one panel's plot area is in the figure and what it shows: the box of the panel's
/// frame (metres for maps; the chart's units for plots) that fills the plot area.
struct PanelInfo {
  std::string name;  ///< see each function
  int x = 0;         ///< top-left corner of the plot area in the figure (px)
  int y = 0;
  int width = 0;     ///< plot area size (px)
  int height = 0;
  Box2 box;          ///< the frame's region shown: min at the bottom-left corner
  std::string title = {};  ///< the title written above a map panel

  /// The figure pixel position of a point in the panel's frame (x right, y up).
  Vec2 ToFigurePixel(const Vec2& p) const {
    const Vec2 s = box.Size();
    return {x + (p.x() - box.min.x()) / s.x() * width, y + (box.max.y() - p.y()) / s.y() * height};
  }
};

struct FigureInfo {
  std::filesystem::path path;
  int width = 0;
  int height = 0;
  std::vector<PanelInfo> panels;
  std::vector<std::string> legend;  ///< the header legend's labels, in order (maps.png)

  /// The panel called `name`; aborts if there is none.
  const PanelInfo& Panel(std::string_view name) const;
};

/// maps.png: panel "world" (W) with the route coloured per map, start and switch points, then
/// panels "map0", "map1", ... (each in its M_k) with path, start and switch point. The world
/// panel is titled MapsRouteTitle(data.route_source); the legend explains the world's shapes
/// only where there are some.
FigureInfo RenderMapsFigure(const MapsFigureData& data, const std::filesystem::path& png,
                            const FigureOptions& options = {});

/// The title of maps.png's world panel: "Ground truth in the world frame W", "Reference
/// trajectory in the world frame W" or "Odometry (no reference) in the odometry frame O".
std::string MapsRouteTitle(RouteSource source);

/// maps_compare.png: panels "map0", "map1", ... side by side, each in its own frame.
FigureInfo RenderMapsCompareFigure(const MapsCompareFigureData& data,
                                   const std::filesystem::path& png,
                                   const FigureOptions& options = {});

struct PlaybackFigureOptions {
  FigureOptions figure;
  double inset_size = 12.0;  ///< m, side of the zoomed square, > 0 (ConfigError otherwise)
  /// Centre of the inset in W; none: where the runs spread most (FindWidestSpread).
  std::optional<Vec2> inset_center;
};

/// playback_<mode>.png: panel "world" (W) with the target path, every run and the inset's
/// frame, and panel "inset" (W) zoomed so that 0.1 m is at least 3 px.
FigureInfo RenderPlaybackFigure(const PlaybackFigureData& data, const std::filesystem::path& png,
                                const PlaybackFigureOptions& options = {});

/// odometry.png: one panel per drive, "drive0", "drive1", ... (W), ground truth and odometry
/// aligned at the start.
FigureInfo RenderOdometryFigure(const OdometryFigureData& data, const std::filesystem::path& png,
                                const FigureOptions& options = {});

struct LikelihoodFigureOptions {
  FigureOptions figure;
  /// true: log-likelihood relative to the maximum, clipped at -log_range (shows the shape of
  /// the basin; with hundreds of beams the likelihood itself is a single bright cell);
  /// false: likelihood normalised to its maximum (linear colour scale).
  bool log_scale = true;
  double log_range = 50.0;  ///< > 0 (ConfigError otherwise)
};

/// likelihood.png: panels "without" and "with" (the grids' frame) and a colour bar.
FigureInfo RenderLikelihoodFigure(const LikelihoodFigureData& data,
                                  const std::filesystem::path& png,
                                  const LikelihoodFigureOptions& options = {});

struct SnapshotFigureOptions {
  FigureOptions figure;
  double view_radius = 12.0;  ///< m, half the side of the main panel around the estimate
  /// m, half the side of the zoomed panel; <= 0: fit the particles and both poses
  double inset_radius = 0.0;
};

/// snapshot.png: panel "map" (M) around the estimate and panel "inset" (M) on the particles.
FigureInfo RenderSnapshotFigure(const SnapshotData& data, const std::filesystem::path& png,
                                const SnapshotFigureOptions& options = {});

/// errors.png: panels "tracking" and "localization", whose frames are (arc length m, error m).
FigureInfo RenderErrorsFigure(const ErrorsFigureData& data, const std::filesystem::path& png,
                              const FigureOptions& options = {});

/// comparison.png: one panel per metric, named after it, bars per mode with error bars. Its
/// frame is (x, value) with the modes' bars centred on x = 0.5, 1.5, ...
FigureInfo RenderComparisonFigure(const ComparisonFigureData& data,
                                  const std::filesystem::path& png,
                                  const FigureOptions& options = {});

/// A world file at a glance (replaces viz/world_sketch for `retrace world`): panel "world".
FigureInfo RenderWorldFigure(const WorldFigureData& data, const std::filesystem::path& png,
                             const FigureOptions& options = {});

/// Where the runs of a playback spread most across the target path.
struct WidestSpread {
  bool found = false;       ///< false with fewer than two runs meeting the target path
  Vec2 point = Vec2::Zero();  ///< the target path point (W)
  double arc_length = 0.0;  ///< m along the target path
  double spread = 0.0;      ///< m, max - min of the runs' signed lateral offsets there
};

/// Samples the target path every `spacing` m; at each station takes each run's nearest
/// position within `max_offset` m and its signed lateral offset, and returns the station with
/// the largest spread (max - min) over at least two runs (the first one on ties).
WidestSpread FindWidestSpread(const std::vector<core::Pose2>& target,
                              const std::vector<Trajectory>& runs, double spacing = 0.5,
                              double max_offset = 3.0);

}  // namespace retrace::viz
