// errors.png: tracking and localization error along the route, map switches marked.

#include <algorithm>
#include <cmath>

#include "viz/figures.hpp"
#include "viz/internal/chart.hpp"
#include "viz/internal/figure_layout.hpp"
#include "viz/style.hpp"

namespace retrace::viz {
namespace {

// Title, subtitle and the legend: each run (or one entry when colours cycle) and the switches.
internal::Header ErrorsHeader(const ErrorsFigureData& data, const FigureOptions& options) {
  const std::size_t n = data.runs.size();
  internal::Header header;
  header.title = options.title.empty()
                     ? "Errors along the route" +
                           (data.mode.empty() ? std::string() : " (" + ModeMaps(data.mode) + ")")
                     : options.title;
  header.subtitle = "Against " + data.x_label.substr(0, data.x_label.rfind(" (")) +
                    "; dashed lines: map switches.";
  if (n <= palette::kRuns.size()) {
    for (std::size_t i = 0; i < n; ++i) {
      header.legend.push_back(
          {data.runs[i].label.empty() ? "run " + std::to_string(i) : data.runs[i].label,
           RunColor(static_cast<int>(i)), internal::LegendSymbol::kLine, Marker::kDisc, 2.0});
    }
  } else {
    header.legend.push_back(
        {"runs (colours cycle)", RunColor(0), internal::LegendSymbol::kLine, Marker::kDisc, 2.0});
  }
  if (!data.switch_arc_lengths.empty()) {
    header.legend.push_back(
        {"map switch", palette::kSwitch, internal::LegendSymbol::kDashedLine, Marker::kDisc, 2.0});
  }
  return header;
}

// The end of the x axis: the farthest finite arc length of a run or a switch (1 if none).
double MaxArcLength(const ErrorsFigureData& data) {
  double s_max = 0.0;
  for (const auto& r : data.runs) {
    for (double s : r.arc_length) {
      if (std::isfinite(s)) s_max = std::max(s_max, s);
    }
  }
  for (double s : data.switch_arc_lengths) {
    if (std::isfinite(s)) s_max = std::max(s_max, s);
  }
  if (!(s_max > 0.0)) s_max = 1.0;
  return s_max;
}

// Panel k (0: tracking, 1: localization error) at y0: axes, switch lines, one line per run and
// the title (saying when outliers are clipped).
PanelInfo PlotErrorPanel(cv::Mat& fig, const ErrorsFigureData& data, int k, int y0, int W,
                         int plot_h, double s_max) {
  const char* names[2] = {"tracking", "localization"};
  const std::string titles[2] = {data.top_title,
                                 "Localization error: estimate vs local ground truth"};
  const std::string y_labels[2] = {data.top_y_label, "localization error (m)"};
  const std::size_t n = data.runs.size();
  std::vector<const std::vector<double>*> series;
  for (const auto& r : data.runs)
    series.push_back(k == 0 ? &r.tracking_error : &r.localization_error);
  bool clipped = false;
  const double y_max = internal::RobustMax(series, &clipped);
  const double y_top =
      internal::NiceStep(y_max, 5) * std::ceil(y_max / internal::NiceStep(y_max, 5) + 1e-9);
  internal::Chart chart;
  chart.plot = cv::Rect(internal::kChartLeft, y0 + internal::kChartTop,
                        W - internal::kChartLeft - internal::kChartRight, plot_h);
  chart.box = Box2::Of(Vec2(0.0, 0.0), Vec2(s_max, std::max(y_top, 1e-3)));
  internal::DrawChartAxes(fig, chart, data.x_label, y_labels[k]);
  for (double s : data.switch_arc_lengths)
    internal::DrawChartVLine(fig, chart, s, palette::kSwitch);
  const int thickness = n > 5 ? 1 : 2;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& r = data.runs[i];
    internal::DrawChartLine(fig, chart, r.arc_length, *series[i], RunColor(static_cast<int>(i)),
                            thickness);
  }
  std::string title = titles[k];
  if (clipped) title += " (outliers clipped at the top)";
  internal::PutText(fig, title, cv::Point(chart.plot.x + chart.plot.width / 2, y0 + 8),
                    internal::Align::kCenter, internal::VAlign::kTop, internal::kPanelTitleText);
  return chart.Info(names[k]);
}

}  // namespace

FigureInfo RenderErrorsFigure(const ErrorsFigureData& data, const std::filesystem::path& png,
                              const FigureOptions& options) {
  options.Validate();
  internal::Require(!data.runs.empty(), png, "the errors figure needs at least one run");
  const int W = options.width;
  const internal::Header header = ErrorsHeader(data, options);
  const double s_max = MaxArcLength(data);

  const int top = internal::HeaderHeight(header, W);
  const int plot_h = 340;
  const int tile_h = internal::kChartTop + plot_h + internal::kChartBottom;
  cv::Mat fig = internal::NewFigure(W, top + 2 * tile_h + 8);
  internal::DrawHeader(fig, header);

  std::vector<PanelInfo> panels;
  for (int k = 0; k < 2; ++k)
    panels.push_back(PlotErrorPanel(fig, data, k, top + k * tile_h, W, plot_h, s_max));
  return internal::FinishFigure(fig, png, std::move(panels));
}

}  // namespace retrace::viz
