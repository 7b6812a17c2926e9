#pragma once
// Assembling figures (private to viz): a header (title, subtitle, legend strip) over tiles;
// map panels are a GL canvas with a frame, tick labels in metres and a title.

#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "viz/figures.hpp"
#include "viz/gl_canvas.hpp"
#include "viz/internal/annotate.hpp"

namespace retrace::viz::internal {

/// Space around a map panel's plot area for its title, ticks and axis labels.
inline constexpr int kPanelLeft = 84;
inline constexpr int kPanelTop = 38;
inline constexpr int kPanelRight = 18;
inline constexpr int kPanelBottom = 62;

struct Header {
  std::string title;
  std::string subtitle;
  std::vector<LegendEntry> legend;
};

/// Height of the header laid out `width` px wide.
int HeaderHeight(const Header& header, int width);
/// Draws the header at the top of `fig`.
void DrawHeader(cv::Mat& fig, const Header& header);

/// A new white RGB figure.
cv::Mat NewFigure(int width, int height);

/// The plot height (px) for a panel `plot_width` wide showing `box` without distortion, the
/// aspect ratio clamped into [min_aspect, max_aspect].
int PlotHeightFor(const Box2& box, int plot_width, double min_aspect, double max_aspect);

/// Tile (outer) and plot (inner) rectangles of a map panel whose tile starts at (x, y).
struct MapPanelRect {
  cv::Rect tile;
  cv::Rect plot;
};
MapPanelRect MapPanelAt(int x, int y, int tile_width, int plot_height);

struct MapPanelStyle {
  std::string x_label = "x (m)";
  std::string y_label = "y (m)";
  bool scale_bar = false;
  /// What is shown where nothing is drawn: white over the world; the unknown grey for maps,
  /// since outside a grid nothing is known either.
  Rgba background = palette::kBackground;
};

/// The style of panels showing an occupancy grid in frame M_k (k < 0: just "x (m)").
MapPanelStyle MapFrameStyle(int k);

/// Renders one map panel: a canvas of the plot's size viewing `view_box` (fit, centred),
/// `draw` fills it, then the pixels go into `fig` with a frame, ticks, axis labels and
/// `title` above, and a scale bar if asked. Returns the panel's placement.
PanelInfo RenderMapPanel(cv::Mat& fig, const MapPanelRect& rect, const Box2& view_box,
                         const std::string& name, const std::string& title, int supersample,
                         const std::function<void(GlCanvas&)>& draw,
                         const MapPanelStyle& style = {});

/// The region RenderMapPanel shows in `rect` when asked for `view_box` (the box grown to the
/// plot's aspect ratio), e.g. to outline an inset on the overview.
Box2 ShownBox(const MapPanelRect& rect, const Box2& view_box);

/// Copies an image into `fig` with its top-left corner at `at`.
void Blit(cv::Mat& fig, const Image& image, cv::Point at);

/// `p` (panel frame, m) as an OpenCV point in the figure.
cv::Point FigurePoint(const PanelInfo& panel, const Vec2& p);

/// Writes `fig` as a PNG and returns its FigureInfo.
FigureInfo FinishFigure(const cv::Mat& fig, const std::filesystem::path& png,
                        std::vector<PanelInfo> panels);

/// Throws core::IoError "<png>: <what>" when `ok` is false: data the figure cannot do without.
void Require(bool ok, const std::filesystem::path& png, const std::string& what);

/// Positions of poses.
std::vector<Vec2> Positions(const std::vector<core::Pose2>& poses);

}  // namespace retrace::viz::internal
