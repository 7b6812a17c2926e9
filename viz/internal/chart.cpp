#include "viz/internal/chart.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "viz/internal/annotate.hpp"
#include "viz/internal/cv_image.hpp"

namespace retrace::viz::internal {
cv::Point2d Chart::Px(double x, double y) const {
  const Vec2 s = box.Size();
  return {plot.x + (x - box.min.x()) / s.x() * plot.width,
          plot.y + (box.max.y() - y) / s.y() * plot.height};
}

void DrawChartAxes(cv::Mat& img, const Chart& chart, const std::string& x_label,
                   const std::string& y_label, bool x_ticks) {
  const cv::Scalar axis = ToScalar(palette::kAxis);
  const cv::Scalar grid = ToScalar(palette::kGridLine);
  const cv::Rect& p = chart.plot;
  const double ys = NiceStep(chart.box.Size().y(), std::max(2, p.height / 60));
  for (double t = std::ceil(chart.box.min.y() / ys) * ys; t <= chart.box.max.y() + 1e-9 * ys; t += ys) {
    const int y = static_cast<int>(std::lround(chart.Px(0.0, t).y));
    cv::line(img, cv::Point(p.x, y), cv::Point(p.x + p.width - 1, y), grid, 1);
    cv::line(img, cv::Point(p.x - 7, y), cv::Point(p.x - 1, y), axis, 1);
    PutText(img, FormatTick(t, ys), cv::Point(p.x - 10, y), Align::kRight, VAlign::kMiddle, kTickText);
  }
  if (x_ticks) {
    const double xs = NiceStep(chart.box.Size().x(), std::max(2, p.width / 110));
    for (double t = std::ceil(chart.box.min.x() / xs) * xs; t <= chart.box.max.x() + 1e-9 * xs; t += xs) {
      const int x = static_cast<int>(std::lround(chart.Px(t, 0.0).x));
      cv::line(img, cv::Point(x, p.y), cv::Point(x, p.y + p.height - 1), grid, 1);
      cv::line(img, cv::Point(x, p.y + p.height), cv::Point(x, p.y + p.height + 6), axis, 1);
      PutText(img, FormatTick(t, xs), cv::Point(x, p.y + p.height + 10), Align::kCenter, VAlign::kTop,
              kTickText);
    }
  }
  cv::rectangle(img, cv::Rect(p.x - 1, p.y - 1, p.width + 2, p.height + 2), axis, 1);
  PutText(img, x_label, cv::Point(p.x + p.width / 2, p.y + p.height + 36), Align::kCenter,
          VAlign::kTop, kLabelText);
  PutTextVertical(img, y_label, cv::Point(p.x - 72, p.y + p.height / 2), kLabelText);
}

void DrawChartLine(cv::Mat& img, const Chart& chart, const std::vector<double>& xs,
                   const std::vector<double>& ys, Rgba color, int thickness) {
  const std::size_t n = std::min(xs.size(), ys.size());
  std::vector<cv::Point> run;
  const cv::Scalar col = ToScalar(color);
  auto flush = [&] {
    if (run.size() >= 2) cv::polylines(img, run, false, col, thickness, cv::LINE_AA, kSubPixelBits);
    run.clear();
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) {
      flush();
      continue;
    }
    const double y = std::clamp(ys[i], chart.box.min.y(), chart.box.max.y());
    const cv::Point q = SubPixel(chart.Px(xs[i], y));
    // Consecutive samples in the same sixteenth of a pixel add nothing.
    if (!run.empty() && run.back() == q) continue;
    run.push_back(q);
  }
  flush();
}

void DrawChartVLine(cv::Mat& img, const Chart& chart, double x, Rgba color) {
  const int px = static_cast<int>(std::lround(chart.Px(x, 0.0).x));
  if (px < chart.plot.x || px > chart.plot.x + chart.plot.width) return;
  for (int y = chart.plot.y; y < chart.plot.y + chart.plot.height; y += 10) {
    cv::line(img, cv::Point(px, y), cv::Point(px, std::min(y + 5, chart.plot.y + chart.plot.height - 1)),
             ToScalar(color), 2);
  }
}

double RobustMax(const std::vector<const std::vector<double>*>& series, bool* clipped) {
  std::vector<double> v;
  for (const auto* s : series) {
    for (double x : *s) {
      if (std::isfinite(x) && x > 0.0) v.push_back(x);
    }
  }
  *clipped = false;
  if (v.empty()) return 1.0;
  const double max = *std::max_element(v.begin(), v.end());
  const std::size_t k = static_cast<std::size_t>(0.99 * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  const double p99 = v[k];
  if (max > 3.0 * p99 && p99 > 0.0) {
    *clipped = true;
    return 1.2 * p99;
  }
  return max;
}

}  // namespace retrace::viz::internal
