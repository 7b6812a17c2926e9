// comparison.png: the map modes' metrics side by side, one bar chart per metric.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "viz/figures.hpp"
#include "viz/internal/chart.hpp"
#include "viz/internal/cv_image.hpp"
#include "viz/internal/figure_layout.hpp"

namespace retrace::viz {
namespace {

std::string ValueLabel(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3g", v);
  return buf;
}

const MetricValue* Find(const ModeMetrics& m, const std::string& metric) {
  for (const auto& v : m.metrics) {
    if (v.metric == metric) return &v;
  }
  return nullptr;
}

}  // namespace

FigureInfo RenderComparisonFigure(const ComparisonFigureData& data,
                                  const std::filesystem::path& png, const FigureOptions& options) {
  options.Validate();
  std::vector<std::string> metrics;
  for (const auto& m : data.modes) {
    for (const auto& v : m.metrics) {
      if (std::find(metrics.begin(), metrics.end(), v.metric) == metrics.end())
        metrics.push_back(v.metric);
    }
  }
  internal::Require(!data.modes.empty() && !metrics.empty(), png,
                    "the comparison figure needs at least one mode with a metric");
  const int W = options.width;
  const int n_modes = static_cast<int>(data.modes.size());

  internal::Header header;
  header.title =
      options.title.empty()
          ? "Map modes compared" + (data.scenario.empty() ? std::string() : ": " + data.scenario)
          : options.title;
  bool intervals = false;
  for (const auto& m : data.modes) {
    for (const auto& v : m.metrics) intervals |= std::isfinite(v.lower) && std::isfinite(v.upper);
  }
  header.subtitle = data.note;
  if (intervals) {
    header.subtitle += std::string(header.subtitle.empty() ? "" : " ") +
                       "Bars: value; whiskers: the interval given with it (e.g. a 95% confidence "
                       "interval).";
  }
  for (int i = 0; i < n_modes; ++i) {
    header.legend.push_back({data.modes[static_cast<std::size_t>(i)].mode,
                             ModeColor(data.modes[static_cast<std::size_t>(i)].mode, i),
                             internal::LegendSymbol::kPatch});
  }

  // Up to three per row; four as two by two.
  const int cols = metrics.size() == 4 ? 2 : std::min<int>(3, static_cast<int>(metrics.size()));
  const int rows = (static_cast<int>(metrics.size()) + cols - 1) / cols;
  const int tile_w = W / cols;
  const int plot_h = 300;
  // Panel titles too long for a tile take more lines; every row then makes room for them.
  std::vector<std::vector<std::string>> titles;
  std::size_t title_lines = 1;
  for (const std::string& metric : metrics) {
    // Centred over the plot, which sits right of the tile's centre: the right half limits.
    titles.push_back(
        internal::WrapText(metric, internal::kPanelTitleText,
                           tile_w - internal::kChartLeft + internal::kChartRight - 12));
    title_lines = std::max(title_lines, titles.back().size());
  }
  const int line_h = internal::TextExtent("Ag", internal::kPanelTitleText).height + 6;
  const int title_extra = static_cast<int>(title_lines - 1) * line_h;
  const int tile_h = internal::kChartTop + title_extra + plot_h + internal::kChartBottom - 20;
  const int top = internal::HeaderHeight(header, W);
  cv::Mat fig = internal::NewFigure(W, top + rows * tile_h + 8);
  internal::DrawHeader(fig, header);

  std::vector<PanelInfo> panels;
  for (std::size_t k = 0; k < metrics.size(); ++k) {
    const int col = static_cast<int>(k) % cols;
    const int row = static_cast<int>(k) / cols;
    double lo = 0.0;
    double hi = 0.0;
    for (const auto& m : data.modes) {
      const MetricValue* v = Find(m, metrics[k]);
      if (v == nullptr) continue;
      for (double x : {v->value, v->lower, v->upper}) {
        if (std::isfinite(x)) {
          lo = std::min(lo, x);
          hi = std::max(hi, x);
        }
      }
    }
    if (!(hi > lo)) hi = lo + 1.0;
    const double step = internal::NiceStep(hi - lo, 5);
    // Headroom for the value labels beyond the bars and whiskers: a share of the whole range,
    // not of the top value, so that a tall interval (or one reaching below 0) keeps its label
    // inside the plot.
    const double margin = 0.12 * (hi - lo);
    const double y_hi = hi > 0.0 ? step * std::ceil((hi + margin) / step) : 0.0;
    const double y_lo = lo < 0.0 ? step * std::floor((lo - margin) / step) : 0.0;
    internal::Chart chart;
    const int x0 = col * tile_w;
    const int y0 = top + row * tile_h;
    chart.plot = cv::Rect(x0 + internal::kChartLeft, y0 + internal::kChartTop + title_extra,
                          tile_w - internal::kChartLeft - internal::kChartRight, plot_h);
    chart.box = Box2::Of(Vec2(0.0, y_lo), Vec2(n_modes, y_hi));
    internal::DrawChartAxes(fig, chart, "", "", false);
    for (std::size_t j = 0; j < titles[k].size(); ++j) {
      internal::PutText(
          fig, titles[k][j],
          cv::Point(chart.plot.x + chart.plot.width / 2, y0 + 8 + static_cast<int>(j) * line_h),
          internal::Align::kCenter, internal::VAlign::kTop, internal::kPanelTitleText);
    }
    const cv::Point2d zero = chart.Px(0.0, 0.0);
    for (int i = 0; i < n_modes; ++i) {
      const ModeMetrics& m = data.modes[static_cast<std::size_t>(i)];
      const cv::Point2d c = chart.Px(i + 0.5, 0.0);
      internal::PutText(fig, m.mode,
                        cv::Point(static_cast<int>(std::lround(c.x)), chart.plot.br().y + 10),
                        internal::Align::kCenter, internal::VAlign::kTop, internal::kLabelText);
      const MetricValue* v = Find(m, metrics[k]);
      if (v == nullptr || !std::isfinite(v->value)) {
        internal::PutText(
            fig, "n/a", cv::Point(static_cast<int>(std::lround(c.x)), static_cast<int>(zero.y) - 8),
            internal::Align::kCenter, internal::VAlign::kBottom, internal::kTickText);
        continue;
      }
      const cv::Point2d a = chart.Px(i + 0.18, v->value);
      const cv::Point2d b = chart.Px(i + 0.82, 0.0);
      const cv::Rect bar(cv::Point(static_cast<int>(std::lround(a.x)),
                                   static_cast<int>(std::lround(std::min(a.y, b.y)))),
                         cv::Point(static_cast<int>(std::lround(b.x)),
                                   static_cast<int>(std::lround(std::max(a.y, b.y)))));
      cv::rectangle(fig, bar, internal::ToScalar(ModeColor(m.mode, i)), cv::FILLED);
      cv::rectangle(fig, bar, internal::ToScalar(palette::kAxis), 1);
      double label_y = v->value;
      if (std::isfinite(v->lower) && std::isfinite(v->upper)) {
        const cv::Point2d l = chart.Px(i + 0.5, v->lower);
        const cv::Point2d u = chart.Px(i + 0.5, v->upper);
        const cv::Scalar black = internal::ToScalar(palette::kText);
        const int cx = static_cast<int>(std::lround(l.x));
        const int ly = static_cast<int>(std::lround(l.y));
        const int uy = static_cast<int>(std::lround(u.y));
        cv::line(fig, cv::Point(cx, ly), cv::Point(cx, uy), black, 2);
        cv::line(fig, cv::Point(cx - 9, ly), cv::Point(cx + 9, ly), black, 2);
        cv::line(fig, cv::Point(cx - 9, uy), cv::Point(cx + 9, uy), black, 2);
        label_y = v->value >= 0.0 ? std::max(v->value, v->upper) : std::min(v->value, v->lower);
      }
      const cv::Point2d lp = chart.Px(i + 0.5, label_y);
      internal::PutText(fig, ValueLabel(v->value),
                        cv::Point(static_cast<int>(std::lround(lp.x)),
                                  static_cast<int>(std::lround(lp.y)) + (label_y >= 0.0 ? -6 : 6)),
                        internal::Align::kCenter,
                        label_y >= 0.0 ? internal::VAlign::kBottom : internal::VAlign::kTop,
                        internal::kTickText);
    }
    panels.push_back(chart.Info(metrics[k]));
  }
  return internal::FinishFigure(fig, png, std::move(panels));
}

}  // namespace retrace::viz
