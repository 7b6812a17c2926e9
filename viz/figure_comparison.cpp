// comparison.png: the map modes' metrics side by side, one bar chart per metric.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "core/format.hpp"
#include "viz/figures.hpp"
#include "viz/internal/chart.hpp"
#include "viz/internal/cv_image.hpp"
#include "viz/internal/figure_layout.hpp"

namespace retrace::viz {
namespace {

// A bar's value label: three significant digits.
std::string ValueLabel(double v) { return core::Printf("%.3g", v); }

// The mode's value of `metric`, or nullptr.
const MetricValue* Find(const ModeMetrics& m, const std::string& metric) {
  for (const auto& v : m.metrics) {
    if (v.metric == metric) return &v;
  }
  return nullptr;
}

// The metric names in the order the modes first give them.
std::vector<std::string> MetricNames(const ComparisonFigureData& data) {
  std::vector<std::string> metrics;
  for (const auto& m : data.modes) {
    for (const auto& v : m.metrics) {
      if (std::find(metrics.begin(), metrics.end(), v.metric) == metrics.end())
        metrics.push_back(v.metric);
    }
  }
  return metrics;
}

// Title, subtitle (the note, and the whiskers explained when there are intervals) and one
// legend patch per mode.
internal::Header ComparisonHeader(const ComparisonFigureData& data, const FigureOptions& options) {
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
  return header;
}

// The grid of metric tiles below the header.
struct TileLayout {
  int cols = 1;
  int rows = 1;
  int tile_w = 0;
  int plot_h = 300;
  int line_h = 0;       ///< one line of a panel title
  int title_extra = 0;  ///< room for the title lines beyond the first
  int tile_h = 0;
  int top = 0;                                   ///< where the tiles start
  std::vector<std::vector<std::string>> titles;  ///< each metric's title, wrapped
};

// Up to three tiles per row (four as two by two), every row tall enough for the longest title.
TileLayout LayOutTiles(const std::vector<std::string>& metrics, const internal::Header& header,
                       int W) {
  TileLayout t;
  t.cols = metrics.size() == 4 ? 2 : std::min<int>(3, static_cast<int>(metrics.size()));
  t.rows = (static_cast<int>(metrics.size()) + t.cols - 1) / t.cols;
  t.tile_w = W / t.cols;
  t.plot_h = 300;
  // Panel titles too long for a tile take more lines; every row then makes room for them.
  std::size_t title_lines = 1;
  for (const std::string& metric : metrics) {
    // Centred over the plot, which sits right of the tile's centre: the right half limits.
    t.titles.push_back(
        internal::WrapText(metric, internal::kPanelTitleText,
                           t.tile_w - internal::kChartLeft + internal::kChartRight - 12));
    title_lines = std::max(title_lines, t.titles.back().size());
  }
  t.line_h = internal::TextExtent("Ag", internal::kPanelTitleText).height + 6;
  t.title_extra = static_cast<int>(title_lines - 1) * t.line_h;
  t.tile_h = internal::kChartTop + t.title_extra + t.plot_h + internal::kChartBottom - 20;
  t.top = internal::HeaderHeight(header, W);
  return t;
}

// The y range of one metric's panel: 0 and every finite value, bound and headroom for labels,
// rounded out to ticks.
std::pair<double, double> MetricYRange(const ComparisonFigureData& data,
                                       const std::string& metric) {
  double lo = 0.0;
  double hi = 0.0;
  for (const auto& m : data.modes) {
    const MetricValue* v = Find(m, metric);
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
  return {y_lo, y_hi};
}

// The whisker of an interval at mode i, from its lower to its upper bound.
void DrawWhisker(cv::Mat& fig, const internal::Chart& chart, int i, const MetricValue& v) {
  const cv::Point2d l = chart.Px(i + 0.5, v.lower);
  const cv::Point2d u = chart.Px(i + 0.5, v.upper);
  const cv::Scalar black = internal::ToScalar(palette::kText);
  const int cx = static_cast<int>(std::lround(l.x));
  const int ly = static_cast<int>(std::lround(l.y));
  const int uy = static_cast<int>(std::lround(u.y));
  cv::line(fig, cv::Point(cx, ly), cv::Point(cx, uy), black, 2);
  cv::line(fig, cv::Point(cx - 9, ly), cv::Point(cx + 9, ly), black, 2);
  cv::line(fig, cv::Point(cx - 9, uy), cv::Point(cx + 9, uy), black, 2);
}

// Mode i's bar with its outline, whisker (if it has an interval) and value label beyond both.
void DrawModeBar(cv::Mat& fig, const internal::Chart& chart, int i, const ModeMetrics& m,
                 const MetricValue& v) {
  const cv::Point2d a = chart.Px(i + 0.18, v.value);
  const cv::Point2d b = chart.Px(i + 0.82, 0.0);
  const cv::Rect bar(cv::Point(static_cast<int>(std::lround(a.x)),
                               static_cast<int>(std::lround(std::min(a.y, b.y)))),
                     cv::Point(static_cast<int>(std::lround(b.x)),
                               static_cast<int>(std::lround(std::max(a.y, b.y)))));
  cv::rectangle(fig, bar, internal::ToScalar(ModeColor(m.mode, i)), cv::FILLED);
  cv::rectangle(fig, bar, internal::ToScalar(palette::kAxis), 1);
  double label_y = v.value;
  if (std::isfinite(v.lower) && std::isfinite(v.upper)) {
    DrawWhisker(fig, chart, i, v);
    label_y = v.value >= 0.0 ? std::max(v.value, v.upper) : std::min(v.value, v.lower);
  }
  const cv::Point2d lp = chart.Px(i + 0.5, label_y);
  internal::PutText(fig, ValueLabel(v.value),
                    cv::Point(static_cast<int>(std::lround(lp.x)),
                              static_cast<int>(std::lround(lp.y)) + (label_y >= 0.0 ? -6 : 6)),
                    internal::Align::kCenter,
                    label_y >= 0.0 ? internal::VAlign::kBottom : internal::VAlign::kTop,
                    internal::kTickText);
}

// Each mode's name under its slot and its bar, or "n/a" where it has no finite value.
void DrawModeBars(cv::Mat& fig, const internal::Chart& chart, const ComparisonFigureData& data,
                  const std::string& metric) {
  const int n_modes = static_cast<int>(data.modes.size());
  const cv::Point2d zero = chart.Px(0.0, 0.0);
  for (int i = 0; i < n_modes; ++i) {
    const ModeMetrics& m = data.modes[static_cast<std::size_t>(i)];
    const cv::Point2d c = chart.Px(i + 0.5, 0.0);
    internal::PutText(fig, m.mode,
                      cv::Point(static_cast<int>(std::lround(c.x)), chart.plot.br().y + 10),
                      internal::Align::kCenter, internal::VAlign::kTop, internal::kLabelText);
    const MetricValue* v = Find(m, metric);
    if (v == nullptr || !std::isfinite(v->value)) {
      internal::PutText(fig, "n/a",
                        cv::Point(static_cast<int>(std::lround(c.x)), static_cast<int>(zero.y) - 8),
                        internal::Align::kCenter, internal::VAlign::kBottom, internal::kTickText);
      continue;
    }
    DrawModeBar(fig, chart, i, m, *v);
  }
}

// The k-th metric's tile: axes, wrapped title and the modes' bars.
PanelInfo DrawMetricPanel(cv::Mat& fig, const ComparisonFigureData& data,
                          const std::vector<std::string>& metrics, const TileLayout& t,
                          std::size_t k) {
  const int n_modes = static_cast<int>(data.modes.size());
  const int col = static_cast<int>(k) % t.cols;
  const int row = static_cast<int>(k) / t.cols;
  const auto [y_lo, y_hi] = MetricYRange(data, metrics[k]);
  internal::Chart chart;
  const int x0 = col * t.tile_w;
  const int y0 = t.top + row * t.tile_h;
  chart.plot = cv::Rect(x0 + internal::kChartLeft, y0 + internal::kChartTop + t.title_extra,
                        t.tile_w - internal::kChartLeft - internal::kChartRight, t.plot_h);
  chart.box = Box2::Of(Vec2(0.0, y_lo), Vec2(n_modes, y_hi));
  internal::DrawChartAxes(fig, chart, "", "", false);
  for (std::size_t j = 0; j < t.titles[k].size(); ++j) {
    internal::PutText(
        fig, t.titles[k][j],
        cv::Point(chart.plot.x + chart.plot.width / 2, y0 + 8 + static_cast<int>(j) * t.line_h),
        internal::Align::kCenter, internal::VAlign::kTop, internal::kPanelTitleText);
  }
  DrawModeBars(fig, chart, data, metrics[k]);
  return chart.Info(metrics[k]);
}

}  // namespace

FigureInfo RenderComparisonFigure(const ComparisonFigureData& data,
                                  const std::filesystem::path& png, const FigureOptions& options) {
  options.Validate();
  const std::vector<std::string> metrics = MetricNames(data);
  internal::Require(!data.modes.empty() && !metrics.empty(), png,
                    "the comparison figure needs at least one mode with a metric");
  const int W = options.width;
  const internal::Header header = ComparisonHeader(data, options);
  const TileLayout t = LayOutTiles(metrics, header, W);
  cv::Mat fig = internal::NewFigure(W, t.top + t.rows * t.tile_h + 8);
  internal::DrawHeader(fig, header);

  std::vector<PanelInfo> panels;
  for (std::size_t k = 0; k < metrics.size(); ++k)
    panels.push_back(DrawMetricPanel(fig, data, metrics, t, k));
  return internal::FinishFigure(fig, png, std::move(panels));
}

}  // namespace retrace::viz
