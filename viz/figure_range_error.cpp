// range_error.png: measured range errors against the fitted beam mixture.

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "viz/internal/annotate.hpp"
#include "viz/internal/chart.hpp"
#include "viz/internal/cv_image.hpp"
#include "viz/internal/figure_layout.hpp"
#include "viz/range_error_figure.hpp"
#include "viz/style.hpp"

namespace retrace::viz {
namespace {

constexpr Rgba kBars{150, 190, 225};
constexpr Rgba kCurve{213, 94, 0};
constexpr double kLogFloorDecades = 6.0;  // a log panel shows at most this many decades

double Shown(double density, bool log_scale) {
  if (!log_scale) return density;
  return density > 0.0 ? std::log10(density) : -std::numeric_limits<double>::infinity();
}

// The y range of a panel: from 0 (linear) or the lowest shown decade (log) to a round top.
Box2 PanelBox(const RangeErrorPanel& p) {
  double top = -std::numeric_limits<double>::infinity();
  double bottom = std::numeric_limits<double>::infinity();
  for (const auto* series : {&p.bin_density, &p.curve_density}) {
    for (double d : *series) {
      const double y = Shown(d, p.log_scale);
      if (!std::isfinite(y)) continue;
      top = std::max(top, y);
      bottom = std::min(bottom, y);
    }
  }
  if (!std::isfinite(top)) top = 1.0;
  if (p.log_scale) {
    top = std::ceil(top + 1e-9);
    bottom =
        std::max(std::floor(std::isfinite(bottom) ? bottom : top - 1.0), top - kLogFloorDecades);
    if (bottom >= top) bottom = top - 1.0;
  } else {
    const double step = internal::NiceStep(std::max(top, 1e-9), 6);
    bottom = 0.0;
    top = step * std::ceil(top / step + 1e-9);
  }
  return Box2::Of(Vec2(p.bin_edges.front(), bottom), Vec2(p.bin_edges.back(), top));
}

void DrawBars(cv::Mat& fig, const internal::Chart& chart, const RangeErrorPanel& p) {
  const cv::Scalar fill = internal::ToScalar(kBars);
  for (std::size_t b = 0; b < p.bin_density.size(); ++b) {
    const double y = Shown(p.bin_density[b], p.log_scale);
    if (!std::isfinite(y) || y <= chart.box.min.y()) continue;
    const cv::Point2d lo = chart.Px(p.bin_edges[b], chart.box.min.y());
    const cv::Point2d hi = chart.Px(p.bin_edges[b + 1], std::min(y, chart.box.max.y()));
    cv::rectangle(
        fig, cv::Point(static_cast<int>(std::lround(lo.x)), static_cast<int>(hi.y)),
        cv::Point(static_cast<int>(std::lround(hi.x)) - 1, static_cast<int>(std::lround(lo.y))),
        fill, cv::FILLED);
  }
}

void RequirePanel(const RangeErrorPanel& p, const std::filesystem::path& png) {
  internal::Require(!p.bin_density.empty() && p.bin_edges.size() == p.bin_density.size() + 1, png,
                    "a range error panel needs bins, one edge more than densities");
  internal::Require(p.curve_error.size() >= 2 && p.curve_density.size() == p.curve_error.size(),
                    png, "a range error panel needs a curve with one density per error");
}

}  // namespace

FigureInfo RenderRangeErrorFigure(const RangeErrorFigureData& data,
                                  const std::filesystem::path& png, const FigureOptions& options) {
  options.Validate();
  internal::Require(!data.panels.empty(), png, "the range error figure needs a panel");
  for (const RangeErrorPanel& p : data.panels) RequirePanel(p, png);
  const int W = options.width;
  internal::Header header;
  header.title =
      options.title.empty() ? "Range error: measured against the fitted beam model" : options.title;
  header.subtitle = data.subtitle;
  header.legend.push_back(
      {data.histogram_label, kBars, internal::LegendSymbol::kPatch, Marker::kDisc, 2.0});
  header.legend.push_back(
      {data.curve_label, kCurve, internal::LegendSymbol::kLine, Marker::kDisc, 2.0});
  const int top = internal::HeaderHeight(header, W);
  const int plot_w = W - internal::kChartLeft - internal::kChartRight;
  const int plot_h = std::clamp(plot_w * 2 / 5, 200, 700);
  const int tile_h = internal::kChartTop + plot_h + internal::kChartBottom;
  const int n = static_cast<int>(data.panels.size());
  cv::Mat fig = internal::NewFigure(W, top + n * tile_h + 8);
  internal::DrawHeader(fig, header);
  std::vector<PanelInfo> panels;
  for (int k = 0; k < n; ++k) {
    const RangeErrorPanel& p = data.panels[static_cast<std::size_t>(k)];
    internal::Chart chart;
    chart.plot =
        cv::Rect(internal::kChartLeft, top + k * tile_h + internal::kChartTop, plot_w, plot_h);
    chart.box = PanelBox(p);
    DrawBars(fig, chart, p);
    internal::DrawChartAxes(fig, chart, "range error z - z* (m)",
                            p.log_scale ? "log10 density (1/m)" : "density (1/m)");
    std::vector<double> ys;
    for (double d : p.curve_density) ys.push_back(Shown(d, p.log_scale));
    internal::DrawChartLine(fig, chart, p.curve_error, ys, kCurve, 2);
    internal::PutText(fig, p.title, cv::Point(chart.plot.x, chart.plot.y - 10),
                      internal::Align::kLeft, internal::VAlign::kBottom, internal::kPanelTitleText);
    panels.push_back(chart.Info(p.name));
  }
  return internal::FinishFigure(fig, png, std::move(panels));
}

}  // namespace retrace::viz
