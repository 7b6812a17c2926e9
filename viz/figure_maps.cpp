// maps.png (paper Fig. 1), maps_compare.png (Fig. 6) and the world overview.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "core/format.hpp"
#include "viz/figures.hpp"
#include "viz/internal/figure_layout.hpp"
#include "viz/internal/layers.hpp"

namespace retrace::viz {
namespace {

using internal::Header;
using internal::LegendEntry;
using internal::LegendSymbol;

// A map panel's title: its label, the size of its known cells and its path length.
std::string MapTitle(const PartialMapView& m, int k) {
  const std::string label = m.label.empty() ? "map " + std::to_string(k) : m.label;
  const Box2 known = internal::KnownCellsBox(m.grid);
  const Vec2 size = known.Size();
  return label + core::Printf(":  %.0f x %.0f m, path %.0f m", size.x(), size.y(),
                              internal::PathLength(m.path));
}

// The box a map panel shows: the occupied cells (or, with none, the observed ones), the path,
// start and switch pose.
Box2 MapBox(const PartialMapView& m) {
  Box2 box = internal::OccupiedCellsBox(m.grid);
  if (box.IsEmpty()) box = internal::KnownCellsBox(m.grid);
  for (const auto& p : m.path) box.Extend(p.translation());
  box.Extend(m.start.translation());
  if (m.switch_pose) box.Extend(m.switch_pose->translation());
  return box.Inflated(2.0);
}

// Draws map k in its own frame: grid, path in `path_color`, start and switch markers.
void DrawMapLayers(GlCanvas& c, const PartialMapView& m, Rgba path_color) {
  c.DrawGrid(m.grid, core::Pose2::Identity());
  c.DrawPolyline(internal::Positions(m.path), 2.5, path_color);
  internal::DrawStart(c, m.start.translation());
  if (m.switch_pose) internal::DrawSwitches(c, {m.switch_pose->translation()});
}

// Columns for n map panels: one row up to three, then rows of two or three.
int MapColumns(std::size_t n) {
  if (n <= 3) return static_cast<int>(std::max<std::size_t>(1, n));
  return n == 4 ? 2 : 3;
}

// Title, subtitle (map count, route length, what the two rows show) and the legend: each
// map's path colour (up to six), start, switches, world (if any) and map cells.
Header MapsHeader(const MapsFigureData& data, const FigureOptions& options,
                  const std::string& route_title) {
  const std::size_t n = data.maps.size();
  Header header;
  header.title = options.title.empty() ? "Teaching: the route in the world and its partial maps"
                                       : options.title;
  std::string top_title = route_title;
  top_title[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(top_title[0])));
  header.subtitle = std::to_string(n) + " partial map" + (n == 1 ? "" : "s") +
                    core::Printf(", route %.0f m. Top: ", internal::PathLength(data.route)) +
                    top_title + ". Bottom: each map in its own frame M_k, built from odometry.";
  for (std::size_t k = 0; k < std::min<std::size_t>(n, 6); ++k) {
    header.legend.push_back({"map " + std::to_string(k) + " path", MapColor(static_cast<int>(k)),
                             LegendSymbol::kLine, Marker::kDisc, 3.0});
  }
  header.legend.push_back(internal::StartLegend());
  if (!data.switch_poses.empty()) header.legend.push_back(internal::SwitchLegend());
  // A log's figure has no world to draw: no buildings, walls or trees to explain.
  if (!data.world.empty()) header.legend.push_back(internal::WorldLegend());
  header.legend.push_back(
      {"map: free / unknown / occupied", palette::kMapUnknown, LegendSymbol::kMapPatch});
  return header;
}

// The top panel's box: the route and switch poses, grown to show the world around them.
Box2 RouteViewBox(const MapsFigureData& data) {
  Box2 world_box;
  for (const auto& p : data.route) world_box.Extend(p.translation());
  for (const auto& p : data.switch_poses) world_box.Extend(p.translation());
  return internal::WorldViewBox(world_box, data.world);
}

// The world, the route in the colour of the map each part of it went into, start and switches.
void DrawRouteLayers(GlCanvas& c, const MapsFigureData& data,
                     const std::vector<std::pair<std::size_t, std::size_t>>& splits) {
  internal::DrawWorld(c, data.world);
  for (std::size_t k = 0; k < splits.size(); ++k) {
    const auto [b, e] = splits[k];
    if (e <= b) continue;
    const std::vector<core::Pose2> part(data.route.begin() + static_cast<std::ptrdiff_t>(b),
                                        data.route.begin() + static_cast<std::ptrdiff_t>(e));
    c.DrawPolyline(internal::Positions(part), 3.0, MapColor(static_cast<int>(k)));
  }
  if (!data.route.empty()) internal::DrawStart(c, data.route.front().translation());
  internal::DrawSwitches(c, internal::Positions(data.switch_poses));
}

// Labels the switch points on the world panel with the map they open.
void LabelSwitches(cv::Mat& fig, const PanelInfo& w, const MapsFigureData& data) {
  for (std::size_t k = 0; k < data.switch_poses.size(); ++k) {
    const cv::Point p = internal::FigurePoint(w, data.switch_poses[k].translation());
    // On the side of the panel with more room, so that labels at the edge stay whole.
    const bool left = p.x > w.x + w.width / 2;
    internal::PutLabel(fig, "-> map " + std::to_string(k + 1), p + cv::Point(left ? -12 : 12, -10),
                       left ? internal::Align::kRight : internal::Align::kLeft,
                       internal::VAlign::kBottom, internal::kSmallText,
                       palette::kBackground.WithAlpha(210), 2);
  }
}

}  // namespace

FigureInfo RenderMapsFigure(const MapsFigureData& data, const std::filesystem::path& png,
                            const FigureOptions& options) {
  options.Validate();
  internal::Require(!data.maps.empty(), png, "the maps figure needs at least one partial map");
  const int W = options.width;
  const std::size_t n = data.maps.size();
  const std::string route_title = MapsRouteTitle(data.route_source);
  const Header header = MapsHeader(data, options, route_title);

  // Top: the world around the route.
  const Box2 world_box = RouteViewBox(data);
  const int plot_w = W - internal::kPanelLeft - internal::kPanelRight;
  const int world_plot_h = internal::PlotHeightFor(world_box, plot_w, 0.35, 0.9);

  const int cols = MapColumns(n);
  const int rows =
      static_cast<int>((n + static_cast<std::size_t>(cols) - 1) / static_cast<std::size_t>(cols));
  const int tile_w = W / cols;
  double aspect = 0.6;
  std::vector<Box2> boxes;
  for (const auto& m : data.maps) {
    boxes.push_back(MapBox(m));
    const Vec2 s = boxes.back().Size();
    if (s.x() > 1e-9) aspect = std::max(aspect, s.y() / s.x());
  }
  const int map_plot_w = tile_w - internal::kPanelLeft - internal::kPanelRight;
  const int map_plot_h = static_cast<int>(std::lround(map_plot_w * std::min(aspect, 1.1)));

  const int top = internal::HeaderHeight(header, W);
  const internal::MapPanelRect world_rect = internal::MapPanelAt(0, top, W, world_plot_h);
  const int maps_top = world_rect.tile.y + world_rect.tile.height + 10;
  const int map_tile_h = internal::MapPanelAt(0, 0, tile_w, map_plot_h).tile.height;
  cv::Mat fig = internal::NewFigure(W, maps_top + rows * map_tile_h + 8);
  internal::DrawHeader(fig, header);

  std::vector<PanelInfo> panels;
  const auto splits = internal::SplitAtSwitches(data.route, data.switch_poses);
  panels.push_back(internal::RenderMapPanel(
      fig, world_rect, world_box, "world", route_title, options.supersample,
      [&](GlCanvas& c) { DrawRouteLayers(c, data, splits); }));
  LabelSwitches(fig, panels.back(), data);

  for (std::size_t k = 0; k < n; ++k) {
    const int col = static_cast<int>(k) % cols;
    const int row = static_cast<int>(k) / cols;
    const internal::MapPanelRect rect =
        internal::MapPanelAt(col * tile_w, maps_top + row * map_tile_h, tile_w, map_plot_h);
    const PartialMapView& m = data.maps[k];
    const int ki = static_cast<int>(k);
    panels.push_back(internal::RenderMapPanel(
        fig, rect, boxes[k], "map" + std::to_string(k), MapTitle(m, ki), options.supersample,
        [&](GlCanvas& c) { DrawMapLayers(c, m, MapColor(ki)); }, internal::MapFrameStyle(ki)));
  }
  FigureInfo info = internal::FinishFigure(fig, png, std::move(panels));
  for (const LegendEntry& entry : header.legend) info.legend.push_back(entry.label);
  return info;
}

std::string MapsRouteTitle(RouteSource source) {
  switch (source) {
    case RouteSource::kGroundTruth:
      return "Ground truth in the world frame W";
    case RouteSource::kReference:
      return "Reference trajectory in the world frame W";
    case RouteSource::kOdometry:
      return "Odometry (no reference) in the odometry frame O";
  }
  return "Route";
}

FigureInfo RenderMapsCompareFigure(const MapsCompareFigureData& data,
                                   const std::filesystem::path& png, const FigureOptions& options) {
  options.Validate();
  internal::Require(!data.maps.empty(), png, "the map comparison needs at least one map");
  const int W = options.width;
  const std::size_t n = data.maps.size();
  Header header;
  header.title = options.title.empty() ? "Maps of the same route" : options.title;
  header.subtitle =
      "Each map in its own frame; the same teaching drive, mapped with different poses.";
  header.legend = {{"taught path", palette::kTaughtPath, LegendSymbol::kLine, Marker::kDisc, 2.5},
                   internal::StartLegend()};
  if (std::any_of(data.maps.begin(), data.maps.end(),
                  [](const PartialMapView& m) { return m.switch_pose.has_value(); })) {
    header.legend.push_back(internal::SwitchLegend());
  }
  header.legend.push_back(
      {"map: free / unknown / occupied", palette::kMapUnknown, LegendSymbol::kMapPatch});

  const int cols = MapColumns(n);
  const int rows =
      static_cast<int>((n + static_cast<std::size_t>(cols) - 1) / static_cast<std::size_t>(cols));
  const int tile_w = W / cols;
  const int plot_w = tile_w - internal::kPanelLeft - internal::kPanelRight;
  std::vector<Box2> boxes;
  double aspect = 0.5;
  for (const auto& m : data.maps) {
    boxes.push_back(MapBox(m));
    const Vec2 s = boxes.back().Size();
    if (s.x() > 1e-9) aspect = std::max(aspect, s.y() / s.x());
  }
  const int plot_h = static_cast<int>(std::lround(plot_w * std::min(aspect, 1.2)));
  const int top = internal::HeaderHeight(header, W);
  const int tile_h = internal::MapPanelAt(0, 0, tile_w, plot_h).tile.height;
  cv::Mat fig = internal::NewFigure(W, top + rows * tile_h + 8);
  internal::DrawHeader(fig, header);
  std::vector<PanelInfo> panels;
  for (std::size_t k = 0; k < n; ++k) {
    const int col = static_cast<int>(k) % cols;
    const int row = static_cast<int>(k) / cols;
    const PartialMapView& m = data.maps[k];
    panels.push_back(internal::RenderMapPanel(
        fig, internal::MapPanelAt(col * tile_w, top + row * tile_h, tile_w, plot_h), boxes[k],
        "map" + std::to_string(k), MapTitle(m, static_cast<int>(k)), options.supersample,
        [&](GlCanvas& c) { DrawMapLayers(c, m, palette::kTaughtPath); },
        internal::MapFrameStyle(-1)));
  }
  return internal::FinishFigure(fig, png, std::move(panels));
}

namespace {

// The world figure's title, extent / route / pedestrian line and legend.
Header WorldHeader(const WorldFigureData& data, const FigureOptions& options) {
  Header header;
  header.title = options.title.empty() ? (data.name.empty() ? std::string("World") : data.name)
                                       : options.title;
  const Vec2 size = data.world.Bounds().Size();
  double route_length = 0.0;
  for (std::size_t i = 1; i < data.route.size(); ++i) {
    route_length += (data.route[i] - data.route[i - 1]).norm();
  }
  header.subtitle = core::Printf("extent %.1f x %.1f m", size.x(), size.y());
  if (!data.route.empty()) header.subtitle += core::Printf(", route %.0f m", route_length);
  if (!data.pedestrians.empty()) {
    header.subtitle += ", " + std::to_string(data.pedestrians.size()) + " pedestrians";
  }
  header.legend.push_back(internal::WorldLegend());
  if (!data.route.empty()) {
    header.legend.push_back(
        {"route", palette::kTaughtPath, LegendSymbol::kLine, Marker::kDisc, 2.5});
    header.legend.push_back(internal::StartLegend());
  }
  if (!data.pedestrians.empty()) {
    header.legend.push_back(
        {"pedestrians", palette::kPedestrian, LegendSymbol::kMarker, Marker::kDisc, 6.0});
  }
  if (data.robot) {
    header.legend.push_back({"robot", palette::kTruth, LegendSymbol::kRing});
  }
  return header;
}

}  // namespace

FigureInfo RenderWorldFigure(const WorldFigureData& data, const std::filesystem::path& png,
                             const FigureOptions& options) {
  options.Validate();
  Box2 box = data.world.Bounds();
  for (const Vec2& p : data.route) box.Extend(p);
  for (const Circle& c : data.pedestrians) box.Extend(c.center, c.radius);
  if (data.robot) box.Extend(data.robot->translation(), data.robot_radius);
  internal::Require(!box.IsEmpty(), png, "nothing to draw");
  box = box.Inflated(1.0);
  const int W = options.width;
  const Header header = WorldHeader(data, options);
  const int plot_w = W - internal::kPanelLeft - internal::kPanelRight;
  const int plot_h = internal::PlotHeightFor(box, plot_w, 0.3, 1.2);
  const int top = internal::HeaderHeight(header, W);
  const internal::MapPanelRect rect = internal::MapPanelAt(0, top, W, plot_h);
  cv::Mat fig = internal::NewFigure(W, rect.tile.y + rect.tile.height + 8);
  internal::DrawHeader(fig, header);
  std::vector<PanelInfo> panels;
  panels.push_back(internal::RenderMapPanel(
      fig, rect, box, "world", "World frame W", options.supersample, [&](GlCanvas& c) {
        internal::DrawWorld(c, data.world);
        c.DrawPolyline(data.route, 2.5, palette::kTaughtPath);
        if (!data.route.empty()) internal::DrawStart(c, data.route.front());
        // True size when zoomed in, never smaller than a marker one can see.
        const double ppm = c.view().pixels_per_meter();
        for (const Circle& p : data.pedestrians) {
          c.DrawMarkers({p.center}, Marker::kDisc, std::max(8.0, 2.0 * p.radius * ppm),
                        palette::kPedestrian);
        }
        if (data.robot) {
          const double r = std::max(data.robot_radius, 7.0 / ppm);
          c.DrawCircle(data.robot->translation(), r, 2.0, palette::kTruth);
          c.DrawPoseArrows({*data.robot}, std::max(14.0, 1.6 * r * ppm), palette::kTruth);
        }
      }));
  return internal::FinishFigure(fig, png, std::move(panels));
}

}  // namespace retrace::viz
