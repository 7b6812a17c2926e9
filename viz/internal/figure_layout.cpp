#include "viz/internal/figure_layout.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/check.hpp"
#include "core/errors.hpp"
#include "viz/internal/cv_image.hpp"

namespace retrace::viz::internal {

int HeaderHeight(const Header& header, int width) {
  int h = 14 + TextExtent(header.title.empty() ? "X" : header.title, kTitleText).height + 8;
  if (!header.subtitle.empty()) h += TextExtent(header.subtitle, kLabelText).height + 8;
  h += LegendHeight(header.legend, width);
  return h + 6;
}

void DrawHeader(cv::Mat& fig, const Header& header) {
  int y = 14;
  PutText(fig, header.title, cv::Point(fig.cols / 2, y), Align::kCenter, VAlign::kTop, kTitleText);
  y += TextExtent(header.title.empty() ? "X" : header.title, kTitleText).height + 8;
  if (!header.subtitle.empty()) {
    const TextStyle sub{kLabelText.scale, 1, palette::kAxis};
    PutText(fig, header.subtitle, cv::Point(fig.cols / 2, y), Align::kCenter, VAlign::kTop, sub);
    y += TextExtent(header.subtitle, kLabelText).height + 8;
  }
  DrawLegend(fig, header.legend, cv::Rect(0, y, fig.cols, LegendHeight(header.legend, fig.cols)));
}

cv::Mat NewFigure(int width, int height) {
  return cv::Mat(std::max(1, height), std::max(1, width), CV_8UC3, ToScalar(palette::kBackground));
}

int PlotHeightFor(const Box2& box, int plot_width, double min_aspect, double max_aspect) {
  const Vec2 s = box.Size();
  const double aspect = s.x() > 1e-9 ? s.y() / s.x() : 1.0;
  return static_cast<int>(std::lround(plot_width * std::clamp(aspect, min_aspect, max_aspect)));
}

MapPanelRect MapPanelAt(int x, int y, int tile_width, int plot_height) {
  MapPanelRect r;
  r.tile = cv::Rect(x, y, tile_width, kPanelTop + plot_height + kPanelBottom);
  r.plot = cv::Rect(x + kPanelLeft, y + kPanelTop, tile_width - kPanelLeft - kPanelRight, plot_height);
  return r;
}

void Blit(cv::Mat& fig, const Image& image, cv::Point at) {
  if (image.empty()) return;
  const cv::Mat m = ToMat(image);
  const cv::Rect dst = cv::Rect(at.x, at.y, m.cols, m.rows) & cv::Rect(0, 0, fig.cols, fig.rows);
  if (dst.area() == 0) return;
  m(cv::Rect(dst.x - at.x, dst.y - at.y, dst.width, dst.height)).copyTo(fig(dst));
}

MapPanelStyle MapFrameStyle(int k) {
  MapPanelStyle s;
  if (k >= 0) {
    s.x_label = "x in M_" + std::to_string(k) + " (m)";
    s.y_label = "y in M_" + std::to_string(k) + " (m)";
  }
  s.background = palette::kMapUnknown;
  return s;
}

Box2 ShownBox(const MapPanelRect& rect, const Box2& view_box) {
  return View::Fit(view_box, rect.plot.width, rect.plot.height, 4.0).VisibleBox();
}

PanelInfo RenderMapPanel(cv::Mat& fig, const MapPanelRect& rect, const Box2& view_box,
                         const std::string& name, const std::string& title, int supersample,
                         const std::function<void(GlCanvas&)>& draw,
                         const MapPanelStyle& panel_style) {
  const View view = View::Fit(view_box, rect.plot.width, rect.plot.height, 4.0);  // as ShownBox
  GlCanvas canvas(rect.plot.width, rect.plot.height, supersample, panel_style.background);
  canvas.SetView(view);
  draw(canvas);
  Blit(fig, canvas.ReadBack(), rect.plot.tl());
  DrawMapAxes(fig, rect.plot, view, panel_style.x_label, panel_style.y_label);
  if (panel_style.scale_bar) DrawScaleBar(fig, rect.plot, view);
  // A long title shrinks to fit its tile rather than run into the next panel.
  TextStyle style = kPanelTitleText;
  while (style.scale > 0.4 && TextExtent(title, style).width > rect.tile.width - 12) style.scale *= 0.94;
  const int cx = std::clamp(rect.plot.x + rect.plot.width / 2,
                            rect.tile.x + TextExtent(title, style).width / 2 + 6,
                            rect.tile.x + rect.tile.width - TextExtent(title, style).width / 2 - 6);
  PutText(fig, title, cv::Point(cx, rect.tile.y + 8), Align::kCenter, VAlign::kTop, style);
  return PanelInfo{name, rect.plot.x, rect.plot.y, rect.plot.width, rect.plot.height,
                   view.VisibleBox(), title};
}

cv::Point FigurePoint(const PanelInfo& panel, const Vec2& p) {
  const Vec2 q = panel.ToFigurePixel(p);
  return {static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y()))};
}

FigureInfo FinishFigure(const cv::Mat& fig, const std::filesystem::path& png,
                        std::vector<PanelInfo> panels) {
  WritePng(FromMat(fig), png);
  FigureInfo info;
  info.path = png;
  info.width = fig.cols;
  info.height = fig.rows;
  info.panels = std::move(panels);
  return info;
}

void Require(bool ok, const std::filesystem::path& png, const std::string& what) {
  if (!ok) throw core::IoError(png.string() + ": " + what);
}

std::vector<Vec2> Positions(const std::vector<core::Pose2>& poses) {
  std::vector<Vec2> out;
  out.reserve(poses.size());
  for (const auto& p : poses) out.push_back(p.translation());
  return out;
}

}  // namespace retrace::viz::internal
