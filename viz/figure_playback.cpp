// playback_<mode>.png (paper Fig. 7): target path and every run's ground truth over the world,
// with a zoomed inset where the runs spread most.

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/errors.hpp"
#include "viz/figures.hpp"
#include "viz/internal/figure_layout.hpp"
#include "viz/internal/layers.hpp"
#include "viz/style.hpp"

namespace retrace::viz {
namespace {

using internal::LegendSymbol;

// The least zoom of the inset: 0.1 m cells at least 3 px.
constexpr double kInsetMinPixelsPerMeter = 30.0;

// World, target path, every run, the start and the switches.
void DrawRuns(GlCanvas& c, const PlaybackFigureData& data, double target_px, double run_px) {
  internal::DrawWorld(c, data.world);
  c.DrawPolyline(internal::Positions(data.target), target_px, palette::kTaughtPath);
  for (std::size_t i = 0; i < data.runs.size(); ++i) {
    c.DrawPolyline(internal::Positions(data.runs[i].poses), run_px,
                   RunColor(static_cast<int>(i)).WithAlpha(225));
  }
  if (!data.target.empty()) internal::DrawStart(c, data.target.front().translation());
  internal::DrawSwitches(c, internal::Positions(data.switch_poses));
}

// The overview's box: the target path and every run, grown to show the world around them.
Box2 PlaybackViewBox(const PlaybackFigureData& data) {
  Box2 box;
  for (const auto& p : data.target) box.Extend(p.translation());
  for (const auto& r : data.runs) {
    for (const auto& p : r.poses) box.Extend(p.translation());
  }
  return internal::WorldViewBox(box, data.world);
}

// Where the inset looks and how wide it is (m).
struct Inset {
  Box2 box;
  double size = 0.0;
};

// The inset: where runs spread most (or where asked, or mid-path), at most a third of the
// overview (an inset must zoom) and small enough for 30 px/m, which keeps 0.1 m visible.
Inset PlaceInset(const PlaybackFigureData& data, const PlaybackFigureOptions& options,
                 const WidestSpread& spread, const Box2& box, int inset_plot_w, int plot_h) {
  Vec2 inset_center;
  if (options.inset_center) {
    inset_center = *options.inset_center;
  } else if (spread.found) {
    inset_center = spread.point;
  } else {
    inset_center = data.target[data.target.size() / 2].translation();
  }
  const double inset_size = std::min({options.inset_size, box.Size().maxCoeff() / 3.0,
                                      std::min(inset_plot_w, plot_h) / kInsetMinPixelsPerMeter});
  const Box2 inset_box = Box2::Of(inset_center - Vec2(0.5 * inset_size, 0.5 * inset_size),
                                  inset_center + Vec2(0.5 * inset_size, 0.5 * inset_size));
  return {inset_box, inset_size};
}

// The legend: target path, each run (or one entry when colours cycle), start, switches (if
// any), inset frame and world.
std::vector<internal::LegendEntry> PlaybackLegend(const PlaybackFigureData& data) {
  std::vector<internal::LegendEntry> legend;
  const std::size_t n = data.runs.size();
  legend.push_back(
      {"target path (taught)", palette::kTaughtPath, LegendSymbol::kLine, Marker::kDisc, 3.0});
  if (n <= palette::kRuns.size()) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::string label =
          data.runs[i].label.empty() ? "run " + std::to_string(i) : data.runs[i].label;
      legend.push_back(
          {label, RunColor(static_cast<int>(i)), LegendSymbol::kLine, Marker::kDisc, 2.0});
    }
  } else {
    legend.push_back(
        {"runs (colours cycle)", RunColor(0), LegendSymbol::kLine, Marker::kDisc, 2.0});
  }
  legend.push_back(internal::StartLegend());
  if (!data.switch_poses.empty()) legend.push_back(internal::SwitchLegend());
  legend.push_back({"inset", palette::kInsetFrame, LegendSymbol::kLine, Marker::kDisc, 2.0});
  legend.push_back(internal::WorldLegend());
  return legend;
}

// Title (mode and run count), subtitle saying what the inset shows, and the legend.
internal::Header PlaybackHeader(const PlaybackFigureData& data,
                                const PlaybackFigureOptions& options, const WidestSpread& spread,
                                double inset_size) {
  const FigureOptions& fo = options.figure;
  internal::Header header;
  const std::size_t n = data.runs.size();
  header.title = !fo.title.empty()
                     ? fo.title
                     : "Playback" +
                           (data.mode.empty() ? std::string() : " (" + ModeMaps(data.mode) + ")") +
                           ": target path and " + std::to_string(n) + " run" + (n == 1 ? "" : "s");
  char sub[256];
  if (spread.found && !options.inset_center) {
    std::snprintf(
        sub, sizeof(sub),
        "Ground truth in the world frame W. Right: %.0f m inset where the runs spread most "
        "(%.2f m across, %.0f m along the target path).",
        inset_size, spread.spread, spread.arc_length);
  } else {
    std::snprintf(sub, sizeof(sub), "Ground truth in the world frame W. Right: %.0f m inset.",
                  inset_size);
  }
  header.subtitle = sub;
  header.legend = PlaybackLegend(data);
  return header;
}

// The whole route with the inset's frame outlined and labelled "inset".
PanelInfo DrawOverviewPanel(cv::Mat& fig, const PlaybackFigureData& data, int supersample,
                            const internal::MapPanelRect& main_rect, const Box2& box,
                            const internal::MapPanelRect& inset_rect, const Box2& inset_box) {
  const Box2 shown = internal::ShownBox(inset_rect, inset_box);
  const std::vector<Vec2> frame{shown.min, Vec2(shown.max.x(), shown.min.y()), shown.max,
                                Vec2(shown.min.x(), shown.max.y())};
  PanelInfo panel = internal::RenderMapPanel(
      fig, main_rect, box, "world", "Whole route", supersample, [&](GlCanvas& c) {
        DrawRuns(c, data, 3.0, 1.6);
        c.DrawPolyline(frame, 2.0, palette::kInsetFrame, true);
      });
  const cv::Point corner = internal::FigurePoint(panel, shown.max);
  internal::PutLabel(fig, "inset", corner + cv::Point(4, -4), internal::Align::kLeft,
                     internal::VAlign::kBottom, internal::kSmallText,
                     palette::kBackground.WithAlpha(210), 2);
  return panel;
}

}  // namespace

FigureInfo RenderPlaybackFigure(const PlaybackFigureData& data, const std::filesystem::path& png,
                                const PlaybackFigureOptions& options) {
  options.figure.Validate();
  if (!(options.inset_size > 0.0)) throw core::ConfigError("inset_size", "must be positive (m)");
  internal::Require(!data.target.empty(), png, "the playback figure needs the target path");
  const FigureOptions& fo = options.figure;
  const int W = fo.width;
  const Box2 box = PlaybackViewBox(data);

  const int main_tile_w = static_cast<int>(std::lround(W * 0.62));
  const int inset_tile_w = W - main_tile_w;
  const int main_plot_w = main_tile_w - internal::kPanelLeft - internal::kPanelRight;
  const int plot_h = std::max(internal::PlotHeightFor(box, main_plot_w, 0.55, 1.1),
                              inset_tile_w - internal::kPanelLeft - internal::kPanelRight);
  const int inset_plot_w = inset_tile_w - internal::kPanelLeft - internal::kPanelRight;

  const WidestSpread spread = FindWidestSpread(data.target, data.runs);
  const Inset inset = PlaceInset(data, options, spread, box, inset_plot_w, plot_h);
  const internal::Header header = PlaybackHeader(data, options, spread, inset.size);

  const int top = internal::HeaderHeight(header, W);
  const internal::MapPanelRect main_rect = internal::MapPanelAt(0, top, main_tile_w, plot_h);
  const internal::MapPanelRect inset_rect =
      internal::MapPanelAt(main_tile_w, top, inset_tile_w, plot_h);
  cv::Mat fig = internal::NewFigure(W, main_rect.tile.y + main_rect.tile.height + 8);
  internal::DrawHeader(fig, header);

  std::vector<PanelInfo> panels;
  panels.push_back(
      DrawOverviewPanel(fig, data, fo.supersample, main_rect, box, inset_rect, inset.box));
  panels.push_back(internal::RenderMapPanel(fig, inset_rect, inset.box, "inset", "Inset (zoomed)",
                                            fo.supersample,
                                            [&](GlCanvas& c) { DrawRuns(c, data, 5.0, 2.2); },
                                            {"x (m)", "y (m)", true, palette::kBackground}));
  return internal::FinishFigure(fig, png, std::move(panels));
}

}  // namespace retrace::viz
