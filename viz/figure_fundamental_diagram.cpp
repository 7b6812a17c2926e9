// fundamental_diagram.png: walking speed against density, reference curve and simulation.

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "viz/fundamental_diagram_figure.hpp"
#include "viz/internal/chart.hpp"
#include "viz/internal/cv_image.hpp"
#include "viz/internal/figure_layout.hpp"
#include "viz/style.hpp"

namespace retrace::viz {
namespace {

constexpr Rgba kFdBand{214, 230, 245};
constexpr Rgba kFdCurve{0, 0, 0};
// One colour per series (Okabe-Ito: vermilion, blue, bluish green, reddish purple).
constexpr std::array<Rgba, 4> kFdSeries{
    {{213, 94, 0}, {0, 114, 178}, {0, 158, 115}, {204, 121, 167}}};
// Horizontal offset (px) between neighbouring series, so that their bars do not overlap.
constexpr double kFdSeriesOffset = 9.0;

// Title, subtitle and the legend: reference curve, its band and the simulated points.
internal::Header DiagramHeader(const FundamentalDiagramFigureData& data,
                               const FigureOptions& options) {
  internal::Header header;
  header.title = options.title.empty() ? "Fundamental diagram" : options.title;
  header.subtitle = data.subtitle;
  header.legend.push_back(
      {data.curve_label, kFdCurve, internal::LegendSymbol::kLine, Marker::kDisc, 2.0});
  header.legend.push_back(
      {data.band_label, kFdBand, internal::LegendSymbol::kPatch, Marker::kDisc, 2.0});
  for (std::size_t k = 0; k < data.series.size(); ++k) {
    header.legend.push_back({data.series[k].label, kFdSeries[k], internal::LegendSymbol::kMarker,
                             Marker::kDisc, 3.0, true});
  }
  return header;
}

// The largest density (curve or point) and the top of the speed axis: a round value above the
// band and every point's mean + sd.
std::pair<double, double> DiagramExtent(const FundamentalDiagramFigureData& data) {
  const std::size_t n = data.curve_density.size();
  double x_max = data.curve_density.back();
  double y_max = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isfinite(data.band_high[i])) y_max = std::max(y_max, data.band_high[i]);
  }
  for (const SpeedSeries& series : data.series) {
    for (const SpeedAtDensity& p : series.points) {
      if (std::isfinite(p.density)) x_max = std::max(x_max, p.density);
      if (std::isfinite(p.mean + p.sd)) y_max = std::max(y_max, p.mean + p.sd);
    }
  }
  const double y_step = internal::NiceStep(std::max(y_max, 0.1), 6);
  const double y_top = y_step * std::ceil(std::max(y_max, 0.1) / y_step + 1e-9);
  return {x_max, y_top};
}

// The band as one filled polygon: along the upper edge, back along the lower one.
void DrawBand(cv::Mat& fig, const internal::Chart& chart, const FundamentalDiagramFigureData& data,
              double y_top) {
  const std::size_t n = data.curve_density.size();
  std::vector<cv::Point> band;
  for (std::size_t i = 0; i < n; ++i) {
    const double y = std::clamp(data.band_high[i], 0.0, y_top);
    band.push_back(internal::SubPixel(chart.Px(data.curve_density[i], y)));
  }
  for (std::size_t i = n; i-- > 0;) {
    const double y = std::clamp(data.band_low[i], 0.0, y_top);
    band.push_back(internal::SubPixel(chart.Px(data.curve_density[i], y)));
  }
  cv::fillPoly(fig, std::vector<std::vector<cv::Point>>{band}, internal::ToScalar(kFdBand),
               cv::LINE_AA, internal::kSubPixelBits);
}

// Each simulated point of `series` as a disc at its mean speed with a capped bar of +- one sd,
// moved `dx` px sideways.
void DrawSimulatedPoints(cv::Mat& fig, const internal::Chart& chart, const SpeedSeries& series,
                         Rgba colour, double dx, double y_top) {
  for (const SpeedAtDensity& p : series.points) {
    if (!std::isfinite(p.density) || !std::isfinite(p.mean)) continue;
    const double sd = std::isfinite(p.sd) ? p.sd : 0.0;
    const cv::Point2d lo =
        chart.Px(p.density, std::clamp(p.mean - sd, 0.0, y_top)) + cv::Point2d(dx, 0.0);
    const cv::Point2d hi =
        chart.Px(p.density, std::clamp(p.mean + sd, 0.0, y_top)) + cv::Point2d(dx, 0.0);
    const cv::Scalar color = internal::ToScalar(colour);
    cv::line(fig, internal::SubPixel(lo), internal::SubPixel(hi), color, 2, cv::LINE_AA,
             internal::kSubPixelBits);
    for (const cv::Point2d& end : {lo, hi}) {
      cv::line(fig, internal::SubPixel(end.x - 6.0, end.y), internal::SubPixel(end.x + 6.0, end.y),
               color, 2, cv::LINE_AA, internal::kSubPixelBits);
    }
    const cv::Point c = internal::SubPixel(chart.Px(p.density, std::clamp(p.mean, 0.0, y_top)) +
                                           cv::Point2d(dx, 0.0));
    cv::circle(fig, c, 6 << internal::kSubPixelBits, color, cv::FILLED, cv::LINE_AA,
               internal::kSubPixelBits);
    cv::circle(fig, c, 6 << internal::kSubPixelBits, internal::ToScalar(palette::kText), 1,
               cv::LINE_AA, internal::kSubPixelBits);
  }
}

}  // namespace

FigureInfo RenderFundamentalDiagramFigure(const FundamentalDiagramFigureData& data,
                                          const std::filesystem::path& png,
                                          const FigureOptions& options) {
  options.Validate();
  const std::size_t n = data.curve_density.size();
  internal::Require(n >= 2, png, "the fundamental diagram needs a reference curve");
  internal::Require(
      data.curve_speed.size() == n && data.band_low.size() == n && data.band_high.size() == n, png,
      "the curve and its band must have one value per density");
  internal::Require(data.series.size() <= kFdSeries.size(), png,
                    "the fundamental diagram draws at most 4 series");
  bool any_point = false;
  for (const SpeedSeries& series : data.series) any_point = any_point || !series.points.empty();
  internal::Require(any_point, png, "the fundamental diagram needs a simulated point");

  const int W = options.width;
  const internal::Header header = DiagramHeader(data, options);
  const int top = internal::HeaderHeight(header, W);
  const int plot_w = W - internal::kChartLeft - internal::kChartRight;
  const int plot_h = std::clamp(plot_w * 3 / 5, 200, 900);
  cv::Mat fig =
      internal::NewFigure(W, top + internal::kChartTop + plot_h + internal::kChartBottom + 8);
  internal::DrawHeader(fig, header);

  internal::Chart chart;
  chart.plot = cv::Rect(internal::kChartLeft, top + internal::kChartTop, plot_w, plot_h);
  const auto [x_max, y_top] = DiagramExtent(data);
  chart.box = Box2::Of(Vec2(0.0, 0.0), Vec2(x_max * 1.04, y_top));

  DrawBand(fig, chart, data, y_top);
  internal::DrawChartAxes(fig, chart, "density (persons/m^2)", "speed along the corridor (m/s)");
  internal::DrawChartLine(fig, chart, data.curve_density, data.curve_speed, kFdCurve, 2);
  for (std::size_t k = 0; k < data.series.size(); ++k) {
    const double dx = kFdSeriesOffset *
                      (static_cast<double>(k) - 0.5 * static_cast<double>(data.series.size() - 1));
    DrawSimulatedPoints(fig, chart, data.series[k], kFdSeries[k], dx, y_top);
  }
  return internal::FinishFigure(fig, png, {chart.Info("speed")});
}

}  // namespace retrace::viz
