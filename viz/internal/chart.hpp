#pragma once
// Line and bar charts drawn with OpenCV (private to viz): a data box mapped onto a plot
// rectangle, axes with round ticks and light grid lines.

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "viz/figures.hpp"
#include "viz/style.hpp"

namespace retrace::viz::internal {

/// Margins of a chart's plot rectangle within its tile.
inline constexpr int kChartLeft = 92;
inline constexpr int kChartTop = 40;
inline constexpr int kChartRight = 24;
inline constexpr int kChartBottom = 64;

struct Chart {
  cv::Rect plot;
  Box2 box;  ///< data units shown by the plot rectangle

  /// Sub-pixel position (x right, y down) of a data point.
  cv::Point2d Px(double x, double y) const;
  PanelInfo Info(const std::string& name) const {
    return {name, plot.x, plot.y, plot.width, plot.height, box};
  }
};

/// Frame, grid lines, ticks and labels; no x ticks when `x_ticks` is false (bar charts label
/// their groups themselves).
void DrawChartAxes(cv::Mat& img, const Chart& chart, const std::string& x_label,
                   const std::string& y_label, bool x_ticks = true);
/// A line through (xs[i], ys[i]); non-finite points break it; y clipped into the box.
void DrawChartLine(cv::Mat& img, const Chart& chart, const std::vector<double>& xs,
                   const std::vector<double>& ys, Rgba color, int thickness);
/// A dashed vertical line at x over the whole plot height.
void DrawChartVLine(cv::Mat& img, const Chart& chart, double x, Rgba color);

/// An upper bound of the data for a y axis starting at 0: the max, or when a few outliers
/// exceed three times the 99th percentile, 1.2 times that percentile (the rest is clipped).
/// Returns 1 when there is no finite positive value. Sets *clipped when values exceed it.
double RobustMax(const std::vector<const std::vector<double>*>& series, bool* clipped);

}  // namespace retrace::viz::internal
