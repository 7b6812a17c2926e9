#pragma once
// Chart pieces for parameter sweeps (private to viz): an x axis for a parameter's values
// (linear, log10 or categorical), ticks at given positions, and points with min-max bars.

#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "viz/internal/chart.hpp"
#include "viz/style.hpp"

namespace retrace::viz::internal {

enum class SweepAxisKind { kLinear, kLog, kCategorical };

/// Where the values of one swept parameter go along a chart's x axis.
struct SweepAxis {
  SweepAxisKind kind = SweepAxisKind::kCategorical;
  std::vector<std::string> labels;  ///< the distinct values in axis order, as printed
  std::vector<double> positions;    ///< frame x of each, ascending
  double lo = 0.0;                  ///< the frame range the chart shows (with margins)
  double hi = 1.0;

  /// Index into labels/positions of a value that MakeSweepAxis saw; -1 otherwise.
  int Index(const std::string& value) const;

  std::map<std::string, int> value_index;  ///< raw value -> index ("300" and "3e2" share one)
};

/// The value as a finite number, if the whole text is one (surrounding blanks allowed).
bool ParseFiniteNumber(const std::string& text, double* value);
/// A number printed for a tick or a legend: up to 6 significant digits, so that
/// 0.30000000000000004 reads 0.3.
std::string FormatValue(double value);

/// The axis for `values` (every value of the parameter, repeats allowed): linear when all are
/// numbers, log10 when moreover all are > 0 and max >= 10 min, categorical otherwise with
/// false before true and other words in order of first appearance.
SweepAxis MakeSweepAxis(const std::vector<std::string>& values);

/// A tick at frame x `at` labelled `label`.
struct AxisTick {
  double at = 0.0;
  std::string label;
};

/// Ticks for `axis` on a plot `plot_width` px wide: one per category; one per value when
/// there are few values (a sweep grid); otherwise round numbers (linear) or 1-2-5 times
/// powers of ten (log).
std::vector<AxisTick> SweepAxisTicks(const SweepAxis& axis, int plot_width);

/// Grid lines, tick marks and labels along the bottom of `chart`; a label that would run
/// into the previous one is left out (its tick stays).
void DrawXTicks(cv::Mat& img, const Chart& chart, const std::vector<AxisTick>& ticks);

/// A vertical bar from `lo` to `hi` (frame y) with short caps at frame x, moved `dx` px.
void DrawRangeBar(cv::Mat& img, const Chart& chart, double x, double dx, double lo, double hi,
                  Rgba color);
/// A disc of `radius` px with a dark outline at frame (x, y), moved `dx` px.
void DrawPointMarker(cv::Mat& img, const Chart& chart, double x, double dx, double y, Rgba color,
                     int radius);
/// Straight lines through frame points (xs[i], ys[i]) each moved `dx` px; non-finite points
/// break the line.
void DrawShiftedLine(cv::Mat& img, const Chart& chart, const std::vector<double>& xs,
                     const std::vector<double>& ys, double dx, Rgba color, int thickness);

}  // namespace retrace::viz::internal
