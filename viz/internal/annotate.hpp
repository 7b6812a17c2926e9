#pragma once
// Text and chart furniture drawn with OpenCV on read-back images (private to viz): titles,
// legends, map axes with tick labels in metres, scale bars, colour bars. Hershey Duplex with
// anti-aliasing: readable at 100% zoom and deterministic.

#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "viz/gl_canvas.hpp"
#include "viz/style.hpp"
#include "viz/view.hpp"

namespace retrace::viz::internal {

struct TextStyle {
  double scale = 0.55;
  int thickness = 1;
  Rgba color = palette::kText;
};

inline constexpr TextStyle kTitleText{0.95, 2, palette::kText};
inline constexpr TextStyle kPanelTitleText{0.68, 1, palette::kText};
inline constexpr TextStyle kLabelText{0.58, 1, palette::kText};
inline constexpr TextStyle kTickText{0.5, 1, palette::kAxis};
inline constexpr TextStyle kSmallText{0.46, 1, palette::kText};

enum class Align { kLeft, kCenter, kRight };
enum class VAlign { kTop, kMiddle, kBottom };

/// Width and height (cap height plus descent) of `text` in pixels.
cv::Size TextExtent(const std::string& text, const TextStyle& style);
/// Draws `text` with its box anchored at `at` as the alignments say.
void PutText(cv::Mat& img, const std::string& text, cv::Point at, Align align, VAlign valign,
             const TextStyle& style);
/// `text` broken at spaces into lines no wider than `max_width` px (a word wider than that
/// stays whole on its own line).
std::vector<std::string> WrapText(const std::string& text, const TextStyle& style, int max_width);
/// The same on a filled box (`pad` px around) for labels over maps and plots.
void PutLabel(cv::Mat& img, const std::string& text, cv::Point at, Align align, VAlign valign,
              const TextStyle& style, Rgba box = palette::kBackground, int pad = 3);
/// Text rotated a quarter turn counter-clockwise (read bottom to top), centred on `center`,
/// drawn on `background`.
void PutTextVertical(cv::Mat& img, const std::string& text, cv::Point center,
                     const TextStyle& style, Rgba background = palette::kBackground);

/// A number with as many decimals as `step` needs ("-0" printed as "0").
std::string FormatTick(double value, double step);
/// A 1, 2 or 5 times a power of ten step giving at most about `max_ticks` over `range`.
double NiceStep(double range, int max_ticks);

/// kMapPatch: three stripes free / unknown / occupied (the colour is ignored).
enum class LegendSymbol { kLine, kMarker, kArrow, kPatch, kRing, kDashedLine, kMapPatch };

struct LegendEntry {
  std::string label;
  Rgba color;
  LegendSymbol symbol = LegendSymbol::kLine;
  Marker marker = Marker::kDisc;  ///< for kMarker
  double size = 3.0;              ///< line width or marker size scale (px)
  bool outlined = false;          ///< markers with a black outline
};

/// Height of `entries` laid out in rows within `width` px.
int LegendHeight(const std::vector<LegendEntry>& entries, int width);
/// Draws the entries left to right, wrapping, centred in `area`.
void DrawLegend(cv::Mat& img, const std::vector<LegendEntry>& entries, cv::Rect area);

/// A frame around `plot` with outward ticks and labels in metres along the bottom and left
/// edges, from the view that maps the panel frame onto the plot area, and axis titles.
void DrawMapAxes(cv::Mat& img, cv::Rect plot, const View& view, const std::string& x_label,
                 const std::string& y_label);
/// A scale bar of a round length in the bottom-left corner of `plot`.
void DrawScaleBar(cv::Mat& img, cv::Rect plot, const View& view);

/// Viridis (perceptually uniform, colour-blind safe), 256 entries from dark to bright.
const std::array<Rgba, 256>& Viridis();
/// A vertical colour bar in `bar` from `lo` (bottom) to `hi` (top) with ticks on the right and
/// a rotated label right of them.
void DrawColorBar(cv::Mat& img, cv::Rect bar, double lo, double hi, const std::string& label);

}  // namespace retrace::viz::internal
