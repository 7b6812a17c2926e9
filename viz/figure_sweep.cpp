// sweep.png: every metric of a parameter sweep against every varied parameter.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "viz/internal/annotate.hpp"
#include "viz/internal/chart.hpp"
#include "viz/internal/chart_sweep.hpp"
#include "viz/internal/cv_image.hpp"
#include "viz/internal/figure_layout.hpp"
#include "viz/sweep_figure.hpp"

namespace retrace::viz {
namespace {

using internal::SweepAxis;

constexpr int kMinColumnWidth = 320;
constexpr int kPlotHeight = 250;
constexpr int kBandPad = 6;

enum class PanelMode { kSeries, kPooled, kScatter };

// How the panels of one parameter's column group the combinations; the same in every row.
struct ColumnPlan {
  PanelMode mode = PanelMode::kSeries;
  std::vector<std::vector<std::size_t>> members;  // combinations of each series
  std::vector<std::string> labels;                // legend label of each series
  std::vector<Rgba> colors;
  std::string heading;  // what the colours mean
  std::string note;     // pooled or scatter, said in words
};

// Mean, min and max of the finite values at one x of one series.
struct SeriesPoint {
  double x = 0.0;
  double mean = 0.0;
  double min = 0.0;
  double max = 0.0;
};

// `parts` joined with `sep` between them.
std::string Join(const std::vector<std::string>& parts, const std::string& sep) {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? sep : "") + parts[i];
  return out;
}

// Whether `s` names a map mode.
bool IsModeName(const std::string& s) {
  return s == "partial" || s == "single" || s == "consistent" || s == "scan_matched";
}

// "tracking_error_m.pooled.rms" -> "tracking error pooled rms (m)": words for the y axis, the
// unit suffix of the house naming rule turned into a unit.
std::string PrettyMetric(const std::string& key) {
  static const std::pair<const char*, const char*> kUnits[] = {
      {"_m", "m"}, {"_rad", "rad"}, {"_s", "s"}, {"_deg", "deg"}, {"_hz", "Hz"}};
  std::vector<std::string> words;
  std::string unit;
  std::size_t start = 0;
  while (start <= key.size()) {
    const std::size_t dot = std::min(key.find('.', start), key.size());
    std::string part = key.substr(start, dot - start);
    for (const auto& [suffix, name] : kUnits) {
      const std::string s = suffix;
      if (part.size() > s.size() && part.compare(part.size() - s.size(), s.size(), s) == 0) {
        part.resize(part.size() - s.size());
        unit = name;
        break;
      }
    }
    std::replace(part.begin(), part.end(), '_', ' ');
    if (!part.empty()) words.push_back(part);
    start = dot + 1;
  }
  std::string out = Join(words, " ");
  return unit.empty() ? out : out + " (" + unit + ")";
}

// `text` broken at spaces into lines at most `width` px wide in `style`.
std::vector<std::string> Wrap(const std::string& text, int width,
                              const internal::TextStyle& style) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    const std::string candidate = line.empty() ? word : line + " " + word;
    if (!line.empty() && internal::TextExtent(candidate, style).width > width) {
      lines.push_back(line);
      line = word;
    } else {
      line = candidate;
    }
    start = end + 1;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

constexpr int kLineStep = 22;  // px per wrapped line of kSmallText / kLabelText

// A text style shrunk until `text` fits in `width` px (not below a readable size).
internal::TextStyle Fit(const std::string& text, internal::TextStyle style, int width) {
  while (style.scale > 0.42 && internal::TextExtent(text, style).width > width) style.scale *= 0.95;
  return style;
}

// The combinations grouped into the series of parameter p's column, keyed by the axis ranks
// of the other parameters so that series sort like the axes.
std::map<std::vector<int>, std::vector<std::size_t>> SeriesGroups(
    const SweepFigureData& data, const std::vector<SweepAxis>& axes, std::size_t p) {
  const std::size_t n_params = data.parameters.size();
  std::map<std::vector<int>, std::vector<std::size_t>> groups;
  for (std::size_t c = 0; c < data.combinations.size(); ++c) {
    std::vector<int> key;
    for (std::size_t q = 0; q < n_params; ++q) {
      if (q != p) key.push_back(axes[q].Index(data.combinations[c].values[q]));
    }
    groups[key].push_back(c);
  }
  return groups;
}

// Whether some series has two x values or more.
bool AnySeriesHasLine(const SweepFigureData& data, const std::vector<SweepAxis>& axes,
                      std::size_t p,
                      const std::map<std::vector<int>, std::vector<std::size_t>>& groups) {
  bool lines = false;
  for (const auto& [key, members] : groups) {
    std::vector<int> xs;
    for (std::size_t c : members) xs.push_back(axes[p].Index(data.combinations[c].values[p]));
    std::sort(xs.begin(), xs.end());
    lines |= std::unique(xs.begin(), xs.end()) - xs.begin() >= 2;
  }
  return lines;
}

// Random sampling: most combinations have a value of parameter p of their own. (In a grid
// every value is shared by all combinations of the others, at least two of them.)
bool IsSampled(const SweepFigureData& data, const std::vector<SweepAxis>& axes, std::size_t p) {
  std::vector<int> xs;
  for (const auto& c : data.combinations) xs.push_back(axes[p].Index(c.values[p]));
  std::sort(xs.begin(), xs.end());
  const auto n_x = static_cast<std::size_t>(std::unique(xs.begin(), xs.end()) - xs.begin());
  return 2 * n_x > data.combinations.size();
}

// A plan with every combination in one series of the first run colour, explained by `note`.
ColumnPlan SingleSeriesPlan(const SweepFigureData& data, PanelMode mode, std::string note) {
  ColumnPlan plan;
  plan.mode = mode;
  plan.members.emplace_back();
  for (std::size_t c = 0; c < data.combinations.size(); ++c) plan.members.back().push_back(c);
  plan.colors.push_back(RunColor(0));
  plan.note = std::move(note);
  return plan;
}

// A plan with one coloured, labelled series per group (mode colours when the one other
// parameter names map modes).
ColumnPlan SeriesPlan(const SweepFigureData& data, const std::vector<SweepAxis>& axes,
                      std::size_t p,
                      const std::map<std::vector<int>, std::vector<std::size_t>>& groups,
                      const std::vector<std::string>& others) {
  ColumnPlan plan;
  bool modes = others.size() == 1;
  for (const auto& [key, members] : groups) {
    std::vector<std::string> parts;
    std::size_t k = 0;
    for (std::size_t q = 0; q < data.parameters.size(); ++q) {
      if (q == p) continue;
      parts.push_back(axes[q].labels[static_cast<std::size_t>(key[k++])]);
    }
    plan.labels.push_back(Join(parts, ", "));
    plan.members.push_back(members);
    modes = modes && IsModeName(plan.labels.back());
  }
  for (std::size_t i = 0; i < plan.labels.size(); ++i) {
    plan.colors.push_back(modes ? ModeColor(plan.labels[i], static_cast<int>(i))
                                : RunColor(static_cast<int>(i)));
  }
  if (!others.empty()) plan.heading = "Colour: " + Join(others, ", ");
  return plan;
}

// How parameter p's column shows its series: scattered, pooled or one line per series.
ColumnPlan PlanColumn(const SweepFigureData& data, const std::vector<SweepAxis>& axes,
                      std::size_t p) {
  const std::size_t n_params = data.parameters.size();
  const auto groups = SeriesGroups(data, axes, p);
  std::vector<std::string> others;
  for (std::size_t q = 0; q < n_params; ++q) {
    if (q != p) others.push_back(data.parameters[q]);
  }
  const bool lines = AnySeriesHasLine(data, axes, p, groups);
  const int n_series = static_cast<int>(groups.size());
  const bool sampled = IsSampled(data, axes, p);
  if (n_series > 1 && (!lines || sampled)) {
    return SingleSeriesPlan(
        data, PanelMode::kScatter,
        sampled ? "Most combinations have a value of their own here (random sampling): "
                  "one dot per case, no lines."
                : "No two combinations share the values of " + Join(others, ", ") +
                      " (random sampling): one dot per case, no lines.");
  }
  if (n_series > kMaxSweepSeries) {
    return SingleSeriesPlan(
        data, PanelMode::kPooled,
        "The " + std::to_string(n_series) + " combinations of " + Join(others, ", ") +
            " are pooled: point = mean, bar = min to max over every case at that value.");
  }
  return SeriesPlan(data, axes, p, groups, others);
}

// The points of one series in panel (metric m, parameter p), ordered along x.
std::vector<SeriesPoint> SeriesPoints(const SweepFigureData& data, const SweepAxis& axis,
                                      std::size_t p, std::size_t m,
                                      const std::vector<std::size_t>& members) {
  std::map<int, std::vector<double>> at;
  for (std::size_t c : members) {
    const SweepCombination& comb = data.combinations[c];
    std::vector<double>& v = at[axis.Index(comb.values[p])];
    for (double x : comb.metrics[m]) {
      if (std::isfinite(x)) v.push_back(x);
    }
  }
  std::vector<SeriesPoint> points;
  for (const auto& [index, values] : at) {
    SeriesPoint pt;
    pt.x = axis.positions[static_cast<std::size_t>(index)];
    if (values.empty()) {
      pt.mean = pt.min = pt.max = std::nan("");
    } else {
      double sum = 0.0;
      for (double x : values) sum += x;
      pt.mean = sum / static_cast<double>(values.size());
      pt.min = *std::min_element(values.begin(), values.end());
      pt.max = *std::max_element(values.begin(), values.end());
    }
    points.push_back(pt);
  }
  return points;
}

// A y range with round ends holding [lo, hi], from 0 when the data are >= 0 and near it.
std::pair<double, double> YRange(double lo, double hi) {
  if (!(lo <= hi)) return {0.0, 1.0};
  if (!(hi > lo)) {
    if (lo >= 0.0) return {0.0, lo > 0.0 ? 1.25 * lo : 1.0};
    return {lo - 0.25 * std::abs(lo), hi + 0.25 * std::abs(lo)};
  }
  const double span = hi - lo;
  double a = lo - 0.06 * span;
  const double b = hi + 0.06 * span;
  if (lo >= 0.0 && (a < 0.0 || lo < 0.3 * hi)) a = 0.0;
  const double step = internal::NiceStep(b - a, 5);
  const double y_lo = std::floor(a / step + 1e-9) * step;
  // Values on the floor of the axis (a success rate of 0) would hide their bar caps in the
  // frame: a sliver below it, too thin for a tick of its own.
  return {lo <= y_lo ? y_lo - 0.04 * (b - y_lo) : y_lo, std::ceil(b / step - 1e-9) * step};
}

// The caption: what a point and a bar are.
std::string Caption(const SweepFigureData& data) {
  std::size_t lo = SIZE_MAX;
  std::size_t hi = 0;
  for (const auto& c : data.combinations) {
    for (const auto& v : c.metrics) {
      lo = std::min(lo, v.size());
      hi = std::max(hi, v.size());
    }
  }
  const std::string n = std::to_string(data.combinations.size()) + " parameter combinations";
  if (hi <= 1)
    return "One case per point (" + n + ", 1 repeat each: no spread over repeats to show).";
  const std::string reps =
      lo == hi ? std::to_string(hi) : std::to_string(lo) + " to " + std::to_string(hi);
  return "Point: mean over repeats; bar: min to max over repeats (" + n + ", " + reps +
         " repeats each).";
}

// What panel (metric m, parameter p) shows: its series (or scatter dots), how many values and
// NaNs it has and the range of the finite ones.
struct PanelValues {
  std::vector<std::vector<SeriesPoint>> series;
  std::vector<std::pair<double, double>> dots;  // scatter: (frame x, value) of every case
  std::size_t n_values = 0;
  std::size_t n_nan = 0;
  double lo = HUGE_VAL;
  double hi = -HUGE_VAL;
};

// The data of panel (metric m, parameter p), gathered first: the y range must hold every
// point and bar.
PanelValues CollectPanelValues(const SweepFigureData& data, const SweepAxis& axis,
                               const ColumnPlan& plan, std::size_t m, std::size_t p) {
  PanelValues d;
  for (const auto& c : data.combinations) {
    for (double v : c.metrics[m]) {
      ++d.n_values;
      if (!std::isfinite(v)) {
        ++d.n_nan;
        continue;
      }
      d.lo = std::min(d.lo, v);
      d.hi = std::max(d.hi, v);
      if (plan.mode == PanelMode::kScatter) {
        d.dots.emplace_back(axis.positions[static_cast<std::size_t>(axis.Index(c.values[p]))], v);
      }
    }
  }
  if (plan.mode != PanelMode::kScatter) {
    for (const auto& members : plan.members)
      d.series.push_back(SeriesPoints(data, axis, p, m, members));
  }
  return d;
}

// Axes, x ticks, axis labels and the title (with its NaN count) of a panel in `tile`.
void DrawPanelFrame(cv::Mat& fig, const internal::Chart& chart, const SweepFigureData& data,
                    const SweepAxis& axis, std::size_t m, std::size_t p, cv::Rect tile,
                    const PanelValues& d) {
  const int plot_w = chart.plot.width;
  std::string x_label = data.parameters[p];
  if (axis.kind == internal::SweepAxisKind::kLog) x_label += " (log scale)";
  const std::string y_label = PrettyMetric(data.metrics[m]);
  internal::DrawChartAxes(fig, chart, "", "", false);
  internal::DrawXTicks(fig, chart, internal::SweepAxisTicks(axis, plot_w));
  internal::PutText(fig, x_label, cv::Point(chart.plot.x + plot_w / 2, chart.plot.br().y + 36),
                    internal::Align::kCenter, internal::VAlign::kTop,
                    Fit(x_label, internal::kLabelText, tile.width - 16));
  internal::PutTextVertical(fig, y_label,
                            cv::Point(chart.plot.x - 72, chart.plot.y + kPlotHeight / 2),
                            Fit(y_label, internal::kLabelText, kPlotHeight));
  std::string title = data.metrics[m];
  if (d.n_nan > 0)
    title += " (" + std::to_string(d.n_nan) + " of " + std::to_string(d.n_values) + " nan)";
  internal::PutText(fig, title, cv::Point(tile.x + tile.width / 2, tile.y + 8),
                    internal::Align::kCenter, internal::VAlign::kTop,
                    Fit(title, internal::kPanelTitleText, tile.width - 16));
}

// "all nan" over every value of the parameter where every case gave NaN (it would otherwise
// just look unswept).
void MarkAllNanValues(cv::Mat& fig, const internal::Chart& chart, const SweepFigureData& data,
                      const SweepAxis& axis, std::size_t m, std::size_t p) {
  std::vector<int> finite(axis.positions.size(), 0);
  for (const auto& c : data.combinations) {
    for (double v : c.metrics[m]) {
      finite[static_cast<std::size_t>(axis.Index(c.values[p]))] += std::isfinite(v) ? 1 : 0;
    }
  }
  for (std::size_t i = 0; i < finite.size(); ++i) {
    if (finite[i] > 0) continue;
    const cv::Point2d at = chart.Px(axis.positions[i], chart.box.min.y());
    internal::PutLabel(fig, "all nan",
                       cv::Point(static_cast<int>(std::lround(at.x)), static_cast<int>(at.y) - 8),
                       internal::Align::kCenter, internal::VAlign::kBottom, internal::kSmallText);
  }
}

// The series' mean lines, then their min-max bars and mean points, series at the same x a few
// pixels apart so that their bars stay readable.
void DrawSeries(cv::Mat& fig, const internal::Chart& chart, const SweepAxis& axis,
                const ColumnPlan& plan, const std::vector<std::vector<SeriesPoint>>& series) {
  double min_gap = chart.plot.width;
  for (std::size_t i = 1; i < axis.positions.size(); ++i) {
    min_gap = std::min(min_gap,
                       chart.Px(axis.positions[i], 0.0).x - chart.Px(axis.positions[i - 1], 0.0).x);
  }
  const double n_s = static_cast<double>(series.size());
  const double dodge = n_s > 1 ? std::min(9.0, 0.4 * min_gap / (n_s - 1.0)) : 0.0;
  for (std::size_t s = 0; s < series.size(); ++s) {
    const double dx = (static_cast<double>(s) - 0.5 * (n_s - 1.0)) * dodge;
    std::vector<double> xs;
    std::vector<double> means;
    for (const SeriesPoint& pt : series[s]) {
      xs.push_back(pt.x);
      means.push_back(pt.mean);
    }
    internal::DrawShiftedLine(fig, chart, xs, means, dx, plan.colors[s], 2);
  }
  for (std::size_t s = 0; s < series.size(); ++s) {
    const double dx = (static_cast<double>(s) - 0.5 * (n_s - 1.0)) * dodge;
    for (const SeriesPoint& pt : series[s]) {
      if (pt.max > pt.min)
        internal::DrawRangeBar(fig, chart, pt.x, dx, pt.min, pt.max, plan.colors[s]);
    }
    for (const SeriesPoint& pt : series[s])
      internal::DrawPointMarker(fig, chart, pt.x, dx, pt.mean, plan.colors[s], 5);
  }
}

// Panel (metric m, parameter p) in `tile`: axes, title, then bars, lines and points.
PanelInfo DrawPanel(cv::Mat& fig, const SweepFigureData& data, const SweepAxis& axis,
                    const ColumnPlan& plan, std::size_t m, std::size_t p, cv::Rect tile) {
  const int plot_w = tile.width - internal::kChartLeft - internal::kChartRight;
  const PanelValues d = CollectPanelValues(data, axis, plan, m, p);
  const auto [y_lo, y_hi] = YRange(d.lo, d.hi);

  internal::Chart chart;
  chart.plot =
      cv::Rect(tile.x + internal::kChartLeft, tile.y + internal::kChartTop, plot_w, kPlotHeight);
  chart.box = Box2::Of(Vec2(axis.lo, y_lo), Vec2(axis.hi, y_hi));
  DrawPanelFrame(fig, chart, data, axis, m, p, tile, d);
  if (d.n_nan == d.n_values) {
    internal::PutText(fig, "no finite value", (chart.plot.tl() + chart.plot.br()) / 2,
                      internal::Align::kCenter, internal::VAlign::kMiddle, internal::kLabelText);
  } else if (plan.mode != PanelMode::kScatter) {
    MarkAllNanValues(fig, chart, data, axis, m, p);
  }

  for (const auto& [x, v] : d.dots)
    internal::DrawPointMarker(fig, chart, x, 0.0, v, plan.colors[0], 4);
  DrawSeries(fig, chart, axis, plan, d.series);
  return chart.Info(data.metrics[m] + " vs " + data.parameters[p]);
}

// Throws unless there are parameters, metrics and cases, each case with one value per
// parameter and one series per metric.
void RequireSweepData(const SweepFigureData& data, const std::filesystem::path& png) {
  internal::Require(!data.parameters.empty(), png,
                    "the sweep figure needs at least one varied parameter");
  internal::Require(!data.metrics.empty(), png, "the sweep figure needs at least one metric");
  internal::Require(!data.combinations.empty(), png, "the sweep figure needs at least one case");
  for (const auto& c : data.combinations) {
    internal::Require(c.values.size() == data.parameters.size(), png,
                      "a combination has " + std::to_string(c.values.size()) +
                          " parameter values for " + std::to_string(data.parameters.size()) +
                          " parameters");
    internal::Require(c.metrics.size() == data.metrics.size(), png,
                      "a combination has " + std::to_string(c.metrics.size()) + " metrics for " +
                          std::to_string(data.metrics.size()) + " metric names");
  }
}

// One x axis per parameter, from its values in the cases.
std::vector<SweepAxis> MakeAxes(const SweepFigureData& data) {
  std::vector<SweepAxis> axes;
  for (std::size_t p = 0; p < data.parameters.size(); ++p) {
    std::vector<std::string> values;
    for (const auto& c : data.combinations) values.push_back(c.values[p]);
    axes.push_back(internal::MakeSweepAxis(values));
  }
  return axes;
}

// A column's legend: one line per labelled series.
std::vector<internal::LegendEntry> ColumnLegend(const ColumnPlan& plan) {
  std::vector<internal::LegendEntry> legend;
  for (std::size_t i = 0; i < plan.labels.size(); ++i) {
    legend.push_back(
        {plan.labels[i], plan.colors[i], internal::LegendSymbol::kLine, Marker::kDisc, 3.0});
  }
  return legend;
}

// Height of the band above the columns: the tallest heading, legend and note, padded (0 when
// no column has any).
int BandHeight(const std::vector<ColumnPlan>& plans,
               const std::vector<std::vector<internal::LegendEntry>>& legends, int tile_w) {
  const int text_w = tile_w - 24;
  int band_h = 0;
  for (std::size_t p = 0; p < plans.size(); ++p) {
    const ColumnPlan& plan = plans[p];
    int h = 0;
    if (!plan.heading.empty())
      h += kLineStep * static_cast<int>(Wrap(plan.heading, text_w, internal::kLabelText).size());
    if (!plan.note.empty())
      h += kLineStep * static_cast<int>(Wrap(plan.note, text_w, internal::kSmallText).size());
    if (!plan.heading.empty()) h += internal::LegendHeight(legends[p], tile_w);
    band_h = std::max(band_h, h);
  }
  if (band_h > 0) band_h += 2 * kBandPad;
  return band_h;
}

// Above column p: what its colours mean (heading and legend) or how it pools (note).
void DrawColumnBand(cv::Mat& fig, const ColumnPlan& plan,
                    const std::vector<internal::LegendEntry>& legend, std::size_t p, int top,
                    int tile_w) {
  const int text_w = tile_w - 24;
  const int x0 = static_cast<int>(p) * tile_w;
  int y = top + kBandPad;
  const int cx = x0 + tile_w / 2;
  for (const std::string& line : Wrap(plan.heading, text_w, internal::kLabelText)) {
    internal::PutText(fig, line, cv::Point(cx, y), internal::Align::kCenter, internal::VAlign::kTop,
                      internal::kLabelText);
    y += kLineStep;
  }
  if (!plan.heading.empty()) {
    const int h = internal::LegendHeight(legend, tile_w);
    internal::DrawLegend(fig, legend, cv::Rect(x0, y - 4, tile_w, h));
    y += h;
  }
  for (const std::string& line : Wrap(plan.note, text_w, internal::kSmallText)) {
    internal::PutText(fig, line, cv::Point(cx, y), internal::Align::kCenter, internal::VAlign::kTop,
                      internal::kSmallText);
    y += kLineStep;
  }
}

}  // namespace

FigureInfo RenderSweepFigure(const SweepFigureData& data, const std::filesystem::path& png,
                             const FigureOptions& options) {
  options.Validate();
  RequireSweepData(data, png);
  const std::size_t n_params = data.parameters.size();
  const std::size_t n_metrics = data.metrics.size();
  const int cols = static_cast<int>(n_params);
  const int W = std::max(options.width, cols * kMinColumnWidth);
  const int tile_w = W / cols;

  const std::vector<SweepAxis> axes = MakeAxes(data);
  std::vector<ColumnPlan> plans;
  for (std::size_t p = 0; p < n_params; ++p) plans.push_back(PlanColumn(data, axes, p));

  internal::Header header;
  header.title = options.title.empty() ? "Parameter sweep" : options.title;
  header.subtitle = Caption(data);

  std::vector<std::vector<internal::LegendEntry>> legends;
  for (const ColumnPlan& plan : plans) legends.push_back(ColumnLegend(plan));
  const int band_h = BandHeight(plans, legends, tile_w);

  const int top = internal::HeaderHeight(header, W);
  const int tile_h = internal::kChartTop + kPlotHeight + internal::kChartBottom;
  cv::Mat fig = internal::NewFigure(W, top + band_h + static_cast<int>(n_metrics) * tile_h + 8);
  internal::DrawHeader(fig, header);
  for (std::size_t p = 0; p < n_params; ++p)
    DrawColumnBand(fig, plans[p], legends[p], p, top, tile_w);

  std::vector<PanelInfo> panels;
  const int rows_top = top + band_h;
  for (std::size_t m = 0; m < n_metrics; ++m) {
    for (std::size_t p = 0; p < n_params; ++p) {
      const cv::Rect tile(static_cast<int>(p) * tile_w, rows_top + static_cast<int>(m) * tile_h,
                          tile_w, tile_h);
      panels.push_back(DrawPanel(fig, data, axes[p], plans[p], m, p, tile));
    }
  }
  return internal::FinishFigure(fig, png, std::move(panels));
}

}  // namespace retrace::viz
