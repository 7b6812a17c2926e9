#pragma once
// An off-screen OpenGL canvas: OSMesa (Mesa's software renderer, no display needed) draws
// world-space primitives through a View into a buffer rendered `supersample` times larger in
// each direction and box-filtered on read-back, which smooths edges deterministically (the
// same calls give the same pixels with the same binary on the same machine).
//
// Sizes: positions and radii of world things are in metres (through the view); line widths
// and marker sizes are in output pixels, so they read the same at any map scale.
//
// Threads: every thread gets its own OSMesa context on first use (kept until the thread ends).
// Several canvases may be alive and drawn in any order in one thread: switching restores the
// canvas's pixels into the context. A canvas must not be used from two threads at once and
// should be destroyed in the thread that drew on it last (figures and video renderers are).

#include <memory>
#include <utility>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "viz/image.hpp"
#include "viz/style.hpp"
#include "viz/view.hpp"

namespace retrace::viz {

/// The largest canvas side (pixels, after supersampling) OSMesa renders.
inline constexpr int kMaxCanvasSide = 16384;

enum class Marker { kDisc, kSquare, kTriangle, kDiamond, kCross };

/// Colours per cell of a regular raster placed in a frame M (a coloured occupancy grid, a
/// likelihood field).
struct CellRaster {
  int width = 0;
  int height = 0;
  double resolution = 0.1;     ///< m per cell
  Vec2 origin = Vec2::Zero();  ///< lower-left corner of cell (0, 0) in M (m)
  std::vector<Rgba> cells;     ///< row-major, row 0 = lowest y, width * height entries
};

/// How an occupancy grid is coloured: a cell at or below `free_probability` is `free`, at or
/// above `occupied_probability` `occupied`; in between the colour blends through `unknown`
/// (p = 0.5). Cells never observed (log-odds exactly 0) are `unknown`, or left out when
/// `unknown_transparent`.
struct GridStyle {
  Rgba free = palette::kMapFree;
  Rgba unknown = palette::kMapUnknown;
  Rgba occupied = palette::kMapOccupied;
  double free_probability = 0.25;
  double occupied_probability = 0.65;
  bool unknown_transparent = false;
};

/// The colour of one cell with log-odds `log_odds` under `style`.
Rgba GridCellColor(float log_odds, const GridStyle& style = {});

class GlCanvas {
 public:
  /// A width x height (output pixels) canvas filled with `background`, rendered internally at
  /// `supersample` (1..4) times the resolution. The view starts as View::Fit of a 1 m box.
  /// Throws RenderError for a non-positive size, a supersampled side above kMaxCanvasSide, or
  /// when OSMesa cannot create or bind an off-screen OpenGL context.
  GlCanvas(int width, int height, int supersample = 2, Rgba background = palette::kBackground);
  ~GlCanvas();
  GlCanvas(GlCanvas&&) noexcept;
  GlCanvas& operator=(GlCanvas&&) noexcept;
  GlCanvas(const GlCanvas&) = delete;
  GlCanvas& operator=(const GlCanvas&) = delete;

  int width() const;
  int height() const;
  int supersample() const;

  /// The world-to-pixel mapping for the following calls; its size must equal the canvas's
  /// (aborts otherwise). Things already drawn stay where they are.
  void SetView(const View& view);
  const View& view() const;

  /// Fills the whole canvas.
  void Clear(Rgba color);

  /// A filled simple or self-intersecting polygon (even-odd rule, so concave rings and
  /// rings with holes given as one path work), points in W (m).
  void FillPolygon(const std::vector<Vec2>& ring_W, Rgba color);
  /// A filled disc, centre in W and radius in m.
  void FillDisc(const Vec2& center_W, double radius, Rgba color);
  /// A circle outline of `width_px` output pixels, centre in W and radius in m.
  void DrawCircle(const Vec2& center_W, double radius, double width_px, Rgba color);
  /// A polyline of `width_px` output pixels through points in W, with round joins. Points
  /// closer than a fraction of a pixel to the simplified line are dropped first (invisible),
  /// so trajectories of many thousands of poses stay cheap. A translucent line covers every
  /// pixel once, even where it crosses itself.
  void DrawPolyline(const std::vector<Vec2>& points_W, double width_px, Rgba color,
                    bool closed = false);
  /// Independent segments (thin walls, edges of imported maps), `width_px` output pixels.
  void DrawSegments(const std::vector<std::pair<Vec2, Vec2>>& segments_W, double width_px,
                    Rgba color);
  /// Markers of `size_px` output pixels (about their diameter) centred on points in W, with an
  /// outline of `outline_px` pixels in `outline` when outline_px > 0.
  void DrawMarkers(const std::vector<Vec2>& points_W, Marker marker, double size_px, Rgba fill,
                   double outline_px = 0.0, Rgba outline = palette::kText);
  /// Heading arrows (darts) of `length_px` output pixels centred on the poses' positions (W),
  /// pointing along their headings; one colour per pose if `colors` has one per pose, else
  /// `color` for all. An outline of `outline_px` pixels in `outline` when outline_px > 0.
  void DrawPoseArrows(const std::vector<core::Pose2>& poses_W, double length_px, Rgba color,
                      const std::vector<Rgba>& colors = {}, double outline_px = 0.0,
                      Rgba outline = palette::kText);
  /// A raster whose frame M sits at X_WM in W, each cell a crisp square (nearest filtering).
  void DrawRaster(const CellRaster& raster_M, const core::Pose2& X_WM);
  /// An occupancy grid in its frame M placed at X_WM in W. Only the visible cells are
  /// converted; where a cell is smaller than a pixel, blocks of cells are pooled first so that
  /// one-cell walls stay visible (an occupied cell in a block wins, then free, then unknown).
  void DrawGrid(const core::OccupancyGrid& grid_M, const core::Pose2& X_WM,
                const GridStyle& style = {});

  /// The canvas as an output-size image (the supersampled pixels averaged per block).
  Image ReadBack();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace retrace::viz
