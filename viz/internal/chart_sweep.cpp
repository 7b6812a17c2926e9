#include "viz/internal/chart_sweep.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "core/format.hpp"
#include "viz/internal/annotate.hpp"
#include "viz/internal/cv_image.hpp"

namespace retrace::viz::internal {
namespace {

// A sweep grid rarely has more values per parameter; beyond this the values are probably
// sampled at random and round-number ticks read better than a tick per value.
constexpr std::size_t kMaxValueTicks = 12;

}  // namespace

int SweepAxis::Index(const std::string& value) const {
  const auto it = value_index.find(value);
  return it == value_index.end() ? -1 : it->second;
}

bool ParseFiniteNumber(const std::string& text, double* value) {
  std::size_t b = text.find_first_not_of(" \t");
  std::size_t e = text.find_last_not_of(" \t");
  if (b == std::string::npos) return false;
  // from_chars takes no leading '+'; "+3" is still a number to a reader.
  if (text[b] == '+') ++b;
  if (b > e) return false;
  const char* first = text.data() + b;
  const char* last = text.data() + e + 1;
  const auto [ptr, ec] = std::from_chars(first, last, *value);
  return ec == std::errc() && ptr == last && std::isfinite(*value);
}

std::string FormatValue(double value) {
  return core::Printf("%.6g", value == 0.0 ? 0.0 : value);  // no "-0"
}

SweepAxis MakeSweepAxis(const std::vector<std::string>& values) {
  SweepAxis axis;
  bool numeric = !values.empty();
  std::vector<double> numbers;
  for (const std::string& v : values) {
    double x = 0.0;
    if (!ParseFiniteNumber(v, &x)) {
      numeric = false;
      break;
    }
    numbers.push_back(x);
  }
  if (numeric) {
    std::vector<double> distinct = numbers;
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    const double min = distinct.front();
    const double max = distinct.back();
    axis.kind = min > 0.0 && max >= 10.0 * min ? SweepAxisKind::kLog : SweepAxisKind::kLinear;
    for (double x : distinct) {
      axis.labels.push_back(FormatValue(x));
      axis.positions.push_back(axis.kind == SweepAxisKind::kLog ? std::log10(x) : x);
    }
    for (std::size_t i = 0; i < values.size(); ++i) {
      const auto it = std::lower_bound(distinct.begin(), distinct.end(), numbers[i]);
      axis.value_index[values[i]] = static_cast<int>(it - distinct.begin());
    }
    const double lo = axis.positions.front();
    const double hi = axis.positions.back();
    // Margins keep the end points and their bars off the frame.
    const double span = hi > lo ? hi - lo : std::max(1.0, std::abs(lo) * 0.2);
    const double pad = hi > lo ? 0.06 * span : 0.5 * span;
    axis.lo = lo - pad;
    axis.hi = hi + pad;
    return axis;
  }
  axis.kind = SweepAxisKind::kCategorical;
  const bool booleans = std::all_of(values.begin(), values.end(), [](const std::string& v) {
    return v == "true" || v == "false";
  });
  std::vector<std::string> order;
  if (booleans) {
    for (const char* b : {"false", "true"}) {
      if (std::find(values.begin(), values.end(), b) != values.end()) order.emplace_back(b);
    }
  } else {
    for (const std::string& v : values) {
      if (std::find(order.begin(), order.end(), v) == order.end()) order.push_back(v);
    }
  }
  for (std::size_t i = 0; i < order.size(); ++i) {
    axis.labels.push_back(order[i]);
    axis.positions.push_back(static_cast<double>(i));
    axis.value_index[order[i]] = static_cast<int>(i);
  }
  axis.lo = -0.5;
  axis.hi = std::max<double>(0.5, static_cast<double>(order.size()) - 0.5);
  return axis;
}

std::vector<AxisTick> SweepAxisTicks(const SweepAxis& axis, int plot_width) {
  std::vector<AxisTick> ticks;
  if (axis.kind == SweepAxisKind::kCategorical || axis.labels.size() <= kMaxValueTicks) {
    for (std::size_t i = 0; i < axis.labels.size(); ++i)
      ticks.push_back({axis.positions[i], axis.labels[i]});
    return ticks;
  }
  if (axis.kind == SweepAxisKind::kLinear) {
    const double step = NiceStep(axis.hi - axis.lo, std::max(2, plot_width / 110));
    for (double t = std::ceil(axis.lo / step) * step; t <= axis.hi + 1e-9 * step; t += step) {
      ticks.push_back({t, FormatTick(t, step)});
    }
    return ticks;
  }
  // Log: every power of ten; 2x and 5x between them when the axis spans few decades.
  const int first = static_cast<int>(std::floor(axis.lo));
  const int last = static_cast<int>(std::ceil(axis.hi));
  const bool minor = last - first <= 3;
  for (int k = first; k <= last; ++k) {
    for (double m : {1.0, 2.0, 5.0}) {
      if (m != 1.0 && !minor) continue;
      const double at = k + std::log10(m);
      if (at < axis.lo - 1e-9 || at > axis.hi + 1e-9) continue;
      ticks.push_back({at, FormatValue(m * std::pow(10.0, k))});
    }
  }
  return ticks;
}

void DrawXTicks(cv::Mat& img, const Chart& chart, const std::vector<AxisTick>& ticks) {
  const cv::Scalar axis = ToScalar(palette::kAxis);
  const cv::Scalar grid = ToScalar(palette::kGridLine);
  const cv::Rect& p = chart.plot;
  int free_from = p.x - 1000;  // the first pixel right of the last label drawn
  for (const AxisTick& t : ticks) {
    const int x = static_cast<int>(std::lround(chart.Px(t.at, chart.box.min.y()).x));
    if (x < p.x || x > p.x + p.width) continue;
    cv::line(img, cv::Point(x, p.y), cv::Point(x, p.y + p.height - 1), grid, 1);
    cv::line(img, cv::Point(x, p.y + p.height), cv::Point(x, p.y + p.height + 6), axis, 1);
    const int w = TextExtent(t.label, kTickText).width;
    if (x - w / 2 < free_from + 8) continue;
    PutText(img, t.label, cv::Point(x, p.y + p.height + 10), Align::kCenter, VAlign::kTop,
            kTickText);
    free_from = x + w - w / 2;
  }
}

void DrawRangeBar(cv::Mat& img, const Chart& chart, double x, double dx, double lo, double hi,
                  Rgba color) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) return;
  const cv::Point2d a = chart.Px(x, lo);
  const cv::Point2d b = chart.Px(x, hi);
  const double px = a.x + dx;
  const cv::Scalar col = ToScalar(color);
  cv::line(img, SubPixel(px, a.y), SubPixel(px, b.y), col, 2, cv::LINE_AA, kSubPixelBits);
  for (double y : {a.y, b.y})
    cv::line(img, SubPixel(px - 5, y), SubPixel(px + 5, y), col, 2, cv::LINE_AA, kSubPixelBits);
}

void DrawPointMarker(cv::Mat& img, const Chart& chart, double x, double dx, double y, Rgba color,
                     int radius) {
  if (!std::isfinite(x) || !std::isfinite(y)) return;
  const cv::Point2d c = chart.Px(x, y);
  const cv::Point q = SubPixel(c.x + dx, c.y);
  cv::circle(img, q, radius * (1 << kSubPixelBits), ToScalar(color), cv::FILLED, cv::LINE_AA,
             kSubPixelBits);
  cv::circle(img, q, radius * (1 << kSubPixelBits), ToScalar(palette::kText), 1, cv::LINE_AA,
             kSubPixelBits);
}

void DrawShiftedLine(cv::Mat& img, const Chart& chart, const std::vector<double>& xs,
                     const std::vector<double>& ys, double dx, Rgba color, int thickness) {
  std::vector<cv::Point> run;
  auto flush = [&] {
    if (run.size() >= 2)
      cv::polylines(img, run, false, ToScalar(color), thickness, cv::LINE_AA, kSubPixelBits);
    run.clear();
  };
  for (std::size_t i = 0; i < std::min(xs.size(), ys.size()); ++i) {
    if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) {
      flush();
      continue;
    }
    const cv::Point2d c = chart.Px(xs[i], ys[i]);
    run.push_back(SubPixel(c.x + dx, c.y));
  }
  flush();
}

}  // namespace retrace::viz::internal
