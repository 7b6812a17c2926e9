#include "viz/internal/annotate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "core/format.hpp"
#include "viz/internal/cv_image.hpp"

namespace retrace::viz::internal {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_DUPLEX;

}  // namespace

cv::Size TextExtent(const std::string& text, const TextStyle& style) {
  int baseline = 0;
  const cv::Size s = cv::getTextSize(text, kFont, style.scale, style.thickness, &baseline);
  return {s.width, s.height + baseline};
}

void PutText(cv::Mat& img, const std::string& text, cv::Point at, Align align, VAlign valign,
             const TextStyle& style) {
  if (text.empty()) return;
  int baseline = 0;
  const cv::Size s = cv::getTextSize(text, kFont, style.scale, style.thickness, &baseline);
  int x = at.x;
  if (align == Align::kCenter) x -= s.width / 2;
  if (align == Align::kRight) x -= s.width;
  const int total = s.height + baseline;
  int top = at.y;
  if (valign == VAlign::kMiddle) top -= total / 2;
  if (valign == VAlign::kBottom) top -= total;
  cv::putText(img, text, cv::Point(x, top + s.height), kFont, style.scale, ToScalar(style.color),
              style.thickness, cv::LINE_AA);
}

std::vector<std::string> WrapText(const std::string& text, const TextStyle& style, int max_width) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t space = std::min(text.find(' ', start), text.size());
    const std::string word = text.substr(start, space - start);
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && TextExtent(longer, style).width > max_width) {
      lines.push_back(line);
      line = word;
    } else {
      line = longer;
    }
    start = space + 1;
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

void PutLabel(cv::Mat& img, const std::string& text, cv::Point at, Align align, VAlign valign,
              const TextStyle& style, Rgba box, int pad) {
  if (text.empty()) return;
  const cv::Size s = TextExtent(text, style);
  int x = at.x;
  if (align == Align::kCenter) x -= s.width / 2;
  if (align == Align::kRight) x -= s.width;
  int y = at.y;
  if (valign == VAlign::kMiddle) y -= s.height / 2;
  if (valign == VAlign::kBottom) y -= s.height;
  const cv::Rect r = cv::Rect(x - pad, y - pad, s.width + 2 * pad, s.height + 2 * pad) &
                     cv::Rect(0, 0, img.cols, img.rows);
  if (box.a == 255) {
    cv::rectangle(img, r, ToScalar(box), cv::FILLED);
  } else if (r.area() > 0) {
    cv::Mat roi = img(r);
    cv::Mat fill(roi.size(), roi.type(), ToScalar(box));
    cv::addWeighted(fill, box.a / 255.0, roi, 1.0 - box.a / 255.0, 0.0, roi);
  }
  PutText(img, text, cv::Point(x, y), Align::kLeft, VAlign::kTop, style);
}

void PutTextVertical(cv::Mat& img, const std::string& text, cv::Point center,
                     const TextStyle& style, Rgba background) {
  if (text.empty()) return;
  const cv::Size s = TextExtent(text, style);
  cv::Mat tmp(s.height + 4, s.width + 4, CV_8UC3, ToScalar(background));
  PutText(tmp, text, cv::Point(2, 2), Align::kLeft, VAlign::kTop, style);
  cv::Mat rot;
  cv::rotate(tmp, rot, cv::ROTATE_90_COUNTERCLOCKWISE);
  const cv::Rect dst(center.x - rot.cols / 2, center.y - rot.rows / 2, rot.cols, rot.rows);
  const cv::Rect clipped = dst & cv::Rect(0, 0, img.cols, img.rows);
  if (clipped.area() == 0) return;
  rot(cv::Rect(clipped.x - dst.x, clipped.y - dst.y, clipped.width, clipped.height))
      .copyTo(img(clipped));
}

std::string FormatTick(double value, double step) {
  // The fewest decimals that write the step exactly: 0.25 needs two, 0.2 one, 2.5 one, 5 none.
  int decimals = 0;
  if (step > 0.0 && std::isfinite(step)) {
    while (decimals < 6) {
      const double scaled = step * std::pow(10.0, decimals);
      if (std::abs(scaled - std::round(scaled)) <= 1e-6 * std::max(1.0, scaled)) break;
      ++decimals;
    }
  }
  if (std::abs(value) < std::abs(step) * 1e-6) value = 0.0;
  return core::FixedText(value, std::clamp(decimals, 0, 6));
}

double NiceStep(double range, int max_ticks) {
  if (!(range > 0.0) || !std::isfinite(range)) return 1.0;
  const double raw = range / std::max(1, max_ticks);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    if (m * mag >= raw) return m * mag;
  }
  return 10.0 * mag;
}

namespace {

constexpr int kLegendSymbolWidth = 34;
constexpr int kLegendGap = 8;
constexpr int kLegendSpacing = 30;
constexpr int kLegendRowHeight = 30;

int EntryWidth(const LegendEntry& e) {
  return kLegendSymbolWidth + kLegendGap + TextExtent(e.label, kLabelText).width;
}

std::vector<std::vector<std::size_t>> LegendRows(const std::vector<LegendEntry>& entries,
                                                 int width) {
  std::vector<std::vector<std::size_t>> rows;
  int x = 0;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const int w = EntryWidth(entries[i]);
    if (rows.empty() || (x > 0 && x + w > width - 20)) {
      rows.emplace_back();
      x = 0;
    }
    rows.back().push_back(i);
    x += w + kLegendSpacing;
  }
  return rows;
}

// The legend's map patch: stripes free / unknown / occupied in a frame, centred on c.
void DrawLegendMapPatch(cv::Mat& img, cv::Point c) {
  const Rgba stripes[3] = {palette::kMapFree, palette::kMapUnknown, palette::kMapOccupied};
  for (int i = 0; i < 3; ++i) {
    cv::rectangle(img, cv::Rect(c.x - 12 + 8 * i, c.y - 8, 8, 16), ToScalar(stripes[i]),
                  cv::FILLED);
  }
  cv::rectangle(img, cv::Rect(c.x - 12, c.y - 8, 24, 16), ToScalar(palette::kWorldEdge), 1);
}

// The legend's pose arrow: a dart pointing right centred on c, outlined if asked.
void DrawLegendArrow(cv::Mat& img, const LegendEntry& e, cv::Point c) {
  const cv::Scalar col = ToScalar(e.color);
  const cv::Scalar black = ToScalar(palette::kText);
  const double L = 20.0;
  std::vector<cv::Point> dart{
      c + cv::Point(static_cast<int>(0.55 * L), 0),
      c + cv::Point(static_cast<int>(-0.45 * L), static_cast<int>(-0.38 * L)),
      c + cv::Point(static_cast<int>(-0.2 * L), 0),
      c + cv::Point(static_cast<int>(-0.45 * L), static_cast<int>(0.38 * L))};
  cv::fillPoly(img, std::vector<std::vector<cv::Point>>{dart}, col, cv::LINE_AA);
  if (e.outlined) cv::polylines(img, dart, true, black, 1, cv::LINE_AA);
}

// The legend's marker (disc, square, triangle, diamond or cross) of radius e.size (at least 3
// px), centred on c, outlined if asked.
void DrawLegendMarker(cv::Mat& img, const LegendEntry& e, cv::Point c) {
  const cv::Scalar col = ToScalar(e.color);
  const cv::Scalar black = ToScalar(palette::kText);
  const int r = std::max(3, static_cast<int>(std::lround(e.size)));
  std::vector<cv::Point> poly;
  switch (e.marker) {
    case Marker::kDisc:
      cv::circle(img, c, r, col, cv::FILLED, cv::LINE_AA);
      if (e.outlined) cv::circle(img, c, r, black, 1, cv::LINE_AA);
      return;
    case Marker::kSquare:
      poly = {c + cv::Point(-r, -r), c + cv::Point(r, -r), c + cv::Point(r, r),
              c + cv::Point(-r, r)};
      break;
    case Marker::kTriangle:
      poly = {c + cv::Point(0, -r), c + cv::Point(r, r * 2 / 3), c + cv::Point(-r, r * 2 / 3)};
      break;
    case Marker::kDiamond:
      poly = {c + cv::Point(0, -r * 6 / 5), c + cv::Point(r, 0), c + cv::Point(0, r * 6 / 5),
              c + cv::Point(-r, 0)};
      break;
    case Marker::kCross:
      cv::line(img, c - cv::Point(r, 0), c + cv::Point(r, 0), col, 2, cv::LINE_AA);
      cv::line(img, c - cv::Point(0, r), c + cv::Point(0, r), col, 2, cv::LINE_AA);
      return;
  }
  cv::fillPoly(img, std::vector<std::vector<cv::Point>>{poly}, col, cv::LINE_AA);
  if (e.outlined) cv::polylines(img, poly, true, black, 1, cv::LINE_AA);
}

// An entry's symbol centred on c.
void DrawLegendSymbol(cv::Mat& img, const LegendEntry& e, cv::Point c) {
  const cv::Scalar col = ToScalar(e.color);
  const int half = kLegendSymbolWidth / 2;
  const int lw = std::max(1, static_cast<int>(std::lround(e.size)));
  switch (e.symbol) {
    case LegendSymbol::kLine:
      cv::line(img, c - cv::Point(half - 2, 0), c + cv::Point(half - 2, 0), col, lw, cv::LINE_AA);
      break;
    case LegendSymbol::kDashedLine:
      for (int x = -half + 2; x < half - 2; x += 8) {
        cv::line(img, c + cv::Point(x, 0), c + cv::Point(std::min(x + 4, half - 2), 0), col, lw,
                 cv::LINE_AA);
      }
      break;
    case LegendSymbol::kPatch:
      cv::rectangle(img, cv::Rect(c.x - 12, c.y - 8, 24, 16), col, cv::FILLED);
      cv::rectangle(img, cv::Rect(c.x - 12, c.y - 8, 24, 16), ToScalar(palette::kWorldEdge), 1);
      break;
    case LegendSymbol::kMapPatch:
      DrawLegendMapPatch(img, c);
      break;
    case LegendSymbol::kRing:
      cv::circle(img, c, 7, col, 2, cv::LINE_AA);
      break;
    case LegendSymbol::kArrow:
      DrawLegendArrow(img, e, c);
      break;
    case LegendSymbol::kMarker:
      DrawLegendMarker(img, e, c);
      break;
  }
}

}  // namespace

int LegendHeight(const std::vector<LegendEntry>& entries, int width) {
  if (entries.empty()) return 0;
  return static_cast<int>(LegendRows(entries, width).size()) * kLegendRowHeight + 8;
}

void DrawLegend(cv::Mat& img, const std::vector<LegendEntry>& entries, cv::Rect area) {
  const auto rows = LegendRows(entries, area.width);
  int y = area.y + 4 + kLegendRowHeight / 2;
  for (const auto& row : rows) {
    int total = 0;
    for (std::size_t i : row) total += EntryWidth(entries[i]) + kLegendSpacing;
    total -= kLegendSpacing;
    int x = area.x + (area.width - total) / 2;
    for (std::size_t i : row) {
      const LegendEntry& e = entries[i];
      DrawLegendSymbol(img, e, cv::Point(x + kLegendSymbolWidth / 2, y));
      PutText(img, e.label, cv::Point(x + kLegendSymbolWidth + kLegendGap, y), Align::kLeft,
              VAlign::kMiddle, kLabelText);
      x += EntryWidth(e) + kLegendSpacing;
    }
    y += kLegendRowHeight;
  }
}

void DrawMapAxes(cv::Mat& img, cv::Rect plot, const View& view, const std::string& x_label,
                 const std::string& y_label) {
  const cv::Scalar axis = ToScalar(palette::kAxis);
  cv::rectangle(img, cv::Rect(plot.x - 1, plot.y - 1, plot.width + 2, plot.height + 2), axis, 1);
  const Box2 box = view.VisibleBox();
  const double ppm = view.pixels_per_meter();
  // About one tick per 110 px keeps labels of four digits apart.
  const double step = NiceStep(box.Size().x(), std::max(2, plot.width / 110));
  const double step_y = NiceStep(box.Size().y(), std::max(2, plot.height / 80));
  const double s = std::max(step, step_y);  // same spacing on both axes: the map is not stretched
  const double s_x = plot.width / (s * ppm) < 2.0 ? step : s;
  const double s_y = plot.height / (s * ppm) < 2.0 ? step_y : s;
  for (double t = std::ceil(box.min.x() / s_x) * s_x; t <= box.max.x() + 1e-9; t += s_x) {
    const int x = plot.x + static_cast<int>(std::lround(view.ToPixel(Vec2(t, 0.0)).x()));
    if (x < plot.x || x > plot.x + plot.width) continue;
    cv::line(img, cv::Point(x, plot.y + plot.height + 1), cv::Point(x, plot.y + plot.height + 7),
             axis, 1);
    PutText(img, FormatTick(t, s_x), cv::Point(x, plot.y + plot.height + 10), Align::kCenter,
            VAlign::kTop, kTickText);
  }
  for (double t = std::ceil(box.min.y() / s_y) * s_y; t <= box.max.y() + 1e-9; t += s_y) {
    const int y = plot.y + static_cast<int>(std::lround(view.ToPixel(Vec2(0.0, t)).y()));
    if (y < plot.y || y > plot.y + plot.height) continue;
    cv::line(img, cv::Point(plot.x - 8, y), cv::Point(plot.x - 2, y), axis, 1);
    PutText(img, FormatTick(t, s_y), cv::Point(plot.x - 11, y), Align::kRight, VAlign::kMiddle,
            kTickText);
  }
  PutText(img, x_label, cv::Point(plot.x + plot.width / 2, plot.y + plot.height + 34),
          Align::kCenter, VAlign::kTop, kLabelText);
  PutTextVertical(img, y_label, cv::Point(plot.x - 64, plot.y + plot.height / 2), kLabelText);
}

void DrawScaleBar(cv::Mat& img, cv::Rect plot, const View& view) {
  const double ppm = view.pixels_per_meter();
  const double target = 0.2 * plot.width / ppm;  // about a fifth of the panel
  double len = NiceStep(target, 1);
  if (len * ppm > 0.3 * plot.width) len /= 2.0;
  const int px = static_cast<int>(std::lround(len * ppm));
  const std::string label = FormatTick(len, len) + " m";
  const cv::Size ts = TextExtent(label, kSmallText);
  const int x0 = plot.x + 14;
  const int y0 = plot.y + plot.height - 14;
  const cv::Rect back(x0 - 8, y0 - ts.height - 18, std::max(px, ts.width) + 16, ts.height + 26);
  cv::Mat roi = img(back & cv::Rect(0, 0, img.cols, img.rows));
  cv::Mat white(roi.size(), roi.type(), ToScalar(palette::kBackground));
  cv::addWeighted(white, 0.8, roi, 0.2, 0.0, roi);
  const cv::Scalar black = ToScalar(palette::kText);
  cv::rectangle(img, cv::Rect(x0, y0 - 5, px, 5), black, cv::FILLED);
  cv::line(img, cv::Point(x0, y0 - 9), cv::Point(x0, y0), black, 1);
  cv::line(img, cv::Point(x0 + px - 1, y0 - 9), cv::Point(x0 + px - 1, y0), black, 1);
  PutText(img, label, cv::Point(x0 + px / 2, y0 - 12), Align::kCenter, VAlign::kBottom, kSmallText);
}

const std::array<Rgba, 256>& Viridis() {
  static const std::array<Rgba, 256> table = [] {
    cv::Mat ramp(1, 256, CV_8UC1);
    for (int i = 0; i < 256; ++i) ramp.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(i);
    cv::Mat bgr;
    cv::applyColorMap(ramp, bgr, cv::COLORMAP_VIRIDIS);
    std::array<Rgba, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const cv::Vec3b c = bgr.at<cv::Vec3b>(0, i);
      t[static_cast<std::size_t>(i)] = {c[2], c[1], c[0], 255};
    }
    return t;
  }();
  return table;
}

void DrawColorBar(cv::Mat& img, cv::Rect bar, double lo, double hi, const std::string& label) {
  const auto& lut = Viridis();
  for (int y = 0; y < bar.height; ++y) {
    const double t = 1.0 - (y + 0.5) / bar.height;
    const Rgba c =
        lut[static_cast<std::size_t>(std::clamp(static_cast<int>(t * 255.0 + 0.5), 0, 255))];
    cv::line(img, cv::Point(bar.x, bar.y + y), cv::Point(bar.x + bar.width - 1, bar.y + y),
             ToScalar(c), 1);
  }
  const cv::Scalar axis = ToScalar(palette::kAxis);
  cv::rectangle(img, cv::Rect(bar.x - 1, bar.y - 1, bar.width + 2, bar.height + 2), axis, 1);
  const double step = NiceStep(hi - lo, std::max(2, bar.height / 70));
  int max_w = 0;
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * std::abs(hi - lo); t += step) {
    const int y = bar.y + static_cast<int>(std::lround((hi - t) / (hi - lo) * bar.height));
    cv::line(img, cv::Point(bar.x + bar.width + 1, y), cv::Point(bar.x + bar.width + 7, y), axis,
             1);
    const std::string s = FormatTick(t, step);
    max_w = std::max(max_w, TextExtent(s, kTickText).width);
    PutText(img, s, cv::Point(bar.x + bar.width + 10, y), Align::kLeft, VAlign::kMiddle, kTickText);
  }
  PutTextVertical(img, label, cv::Point(bar.x + bar.width + 24 + max_w, bar.y + bar.height / 2),
                  kLabelText);
}

}  // namespace retrace::viz::internal
