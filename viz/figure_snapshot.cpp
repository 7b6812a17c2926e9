// snapshot.png (paper Fig. 4): one localization moment in the map frame.

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "viz/figures.hpp"
#include "viz/internal/figure_layout.hpp"
#include "viz/internal/layers.hpp"
#include "viz/internal/snapshot_layers.hpp"

namespace retrace::viz {
namespace {

// The inset's box: a square of inset_radius around the estimate, or else one holding the
// particles, estimate and truth (at least 1 m and at most `r` each side of its centre).
Box2 SnapshotInsetBox(const SnapshotData& data, const SnapshotFigureOptions& options, double r) {
  const Vec2 c = data.estimate.translation();
  if (options.inset_radius > 0.0) {
    return Box2::Of(c - Vec2(options.inset_radius, options.inset_radius),
                    c + Vec2(options.inset_radius, options.inset_radius));
  }
  Box2 b;
  for (const auto& p : data.particles) b.Extend(p.translation());
  b.Extend(data.estimate.translation(), data.robot_radius);
  b.Extend(data.truth.translation(), data.robot_radius);
  b = b.Inflated(0.3);
  const double half = std::clamp(0.5 * b.Size().maxCoeff(), 1.0, r);
  return Box2::Of(b.Center() - Vec2(half, half), b.Center() + Vec2(half, half));
}

// The subtitle: particle and scan point counts (used, rejected, hitting pedestrians) and the
// distance of the estimate from the truth or the log's reference.
std::string SnapshotSubtitle(const SnapshotData& data) {
  int used = 0;
  int rejected = 0;
  int ped = 0;
  for (const ScanPoint& s : data.scan) {
    (s.rejected ? rejected : used) += 1;
    ped += s.hits_pedestrian ? 1 : 0;
  }
  char sub[256];
  if (data.simulated) {
    std::snprintf(sub, sizeof(sub),
                  "Map frame M_%d. %zu particles (opacity: weight), %zu scan points: %d not "
                  "rejected, %d rejected, %d hit pedestrians. Position error %.2f m.",
                  data.map_index, data.particles.size(), data.scan.size(), used, rejected, ped,
                  core::Distance(data.estimate, data.truth));
  } else {
    std::snprintf(sub, sizeof(sub),
                  "Map frame M_%d, a recorded log. %zu particles (opacity: weight), %zu scan "
                  "points: %d not rejected, %d rejected. Distance to the reference %.2f m.",
                  data.map_index, data.particles.size(), data.scan.size(), used, rejected,
                  core::Distance(data.estimate, data.truth));
  }
  return sub;
}

// The localization legend (for a log without pedestrians, its truth called the reference)
// and the inset frame.
std::vector<internal::LegendEntry> SnapshotLegend(const SnapshotData& data) {
  std::vector<internal::LegendEntry> legend = internal::LocalizationLegend();
  if (!data.simulated) {
    // A log knows no pedestrians, and its truth is its reference.
    std::erase_if(legend, [](const internal::LegendEntry& e) {
      return e.label.find("pedestrian") != std::string::npos;
    });
    for (internal::LegendEntry& e : legend) {
      if (e.label == "ground truth") e.label = "reference";
    }
  }
  legend.push_back(
      {"inset", palette::kInsetFrame, internal::LegendSymbol::kLine, Marker::kDisc, 2.0});
  return legend;
}

// Title (time and map), subtitle and legend.
internal::Header SnapshotHeader(const SnapshotData& data, const FigureOptions& fo) {
  internal::Header header;
  char title[128];
  std::snprintf(title, sizeof(title), "Localization snapshot: t = %.1f s, map %d", data.time_s,
                data.map_index);
  header.title = fo.title.empty() ? title : fo.title;
  header.subtitle = SnapshotSubtitle(data);
  header.legend = SnapshotLegend(data);
  return header;
}

// The snapshot's localization layers (references into `data`).
internal::LocalizationLayers LayersOf(const SnapshotData& data) {
  return {.grid = data.grid,
          .path = data.path,
          .particles = data.particles,
          .weights = data.weights,
          .estimate = data.estimate,
          .truth = data.truth,
          .scan = data.scan,
          .pedestrians = data.pedestrians,
          .robot_radius = data.robot_radius};
}

}  // namespace

FigureInfo RenderSnapshotFigure(const SnapshotData& data, const std::filesystem::path& png,
                                const SnapshotFigureOptions& options) {
  options.figure.Validate();
  const FigureOptions& fo = options.figure;
  const int W = fo.width;
  const int main_tile_w = static_cast<int>(std::lround(W * 0.62));
  const int inset_tile_w = W - main_tile_w;
  const int main_plot_w = main_tile_w - internal::kPanelLeft - internal::kPanelRight;
  const int plot_h = main_plot_w;

  const Vec2 c = data.estimate.translation();
  const double r = options.view_radius > 0.0 ? options.view_radius : 12.0;
  const Box2 main_box = Box2::Of(c - Vec2(r, r), c + Vec2(r, r));
  const Box2 inset_box = SnapshotInsetBox(data, options, r);
  const internal::Header header = SnapshotHeader(data, fo);

  const int top = internal::HeaderHeight(header, W);
  const internal::MapPanelRect main_rect = internal::MapPanelAt(0, top, main_tile_w, plot_h);
  const internal::MapPanelRect inset_rect =
      internal::MapPanelAt(main_tile_w, top, inset_tile_w, plot_h);
  cv::Mat fig = internal::NewFigure(W, std::max(main_rect.tile.br().y, inset_rect.tile.br().y) + 8);
  internal::DrawHeader(fig, header);

  const internal::MapPanelStyle style = internal::MapFrameStyle(data.map_index);
  internal::MapPanelStyle inset_style = style;
  inset_style.scale_bar = true;
  const Box2 shown = internal::ShownBox(inset_rect, inset_box);
  const std::vector<Vec2> frame{shown.min, Vec2(shown.max.x(), shown.min.y()), shown.max,
                                Vec2(shown.min.x(), shown.max.y())};
  const internal::LocalizationLayers layers = LayersOf(data);
  std::vector<PanelInfo> panels;
  panels.push_back(internal::RenderMapPanel(
      fig, main_rect, main_box, "map", "Map, scan and particles", fo.supersample,
      [&](GlCanvas& cv) {
        internal::DrawLocalizationLayers(cv, layers, 1.0);
        cv.DrawPolyline(frame, 2.0, palette::kInsetFrame, true);
      },
      style));
  panels.push_back(internal::RenderMapPanel(
      fig, inset_rect, inset_box, "inset", "Particles, estimate and truth (zoomed)", fo.supersample,
      [&](GlCanvas& cv) { internal::DrawLocalizationLayers(cv, layers, 1.6); }, inset_style));
  return internal::FinishFigure(fig, png, std::move(panels));
}

}  // namespace retrace::viz
