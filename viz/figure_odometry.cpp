// odometry.png (paper Fig. 8): ground truth vs wheel odometry of the teaching drive and of a
// playback run, the odometry aligned with the truth at the start.

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "viz/figures.hpp"
#include "viz/internal/figure_layout.hpp"
#include "viz/internal/layers.hpp"

namespace retrace::viz {
namespace {

using internal::LegendSymbol;

// Odometry X_OR carried into W so that its first pose is the first ground-truth pose.
std::vector<core::Pose2> AlignedOdometry(const OdometryDrive& d) {
  std::vector<core::Pose2> out;
  if (d.odometry.empty() || d.truth.empty()) return out;
  const core::Pose2 X_WO = d.truth.front() * d.odometry.front().Inverse();
  out.reserve(d.odometry.size());
  for (const auto& X_OR : d.odometry) out.push_back(X_WO * X_OR);
  return out;
}

// Title, subtitle and the legend: truth, odometry, start, end and the world.
internal::Header OdometryHeader(const FigureOptions& options) {
  internal::Header header;
  header.title = options.title.empty() ? "Ground truth vs wheel odometry" : options.title;
  header.subtitle =
      "World frame W; odometry placed so that it starts at the true start pose. "
      "Squares: where each trajectory ends.";
  header.legend = {{"ground truth", palette::kTruth, LegendSymbol::kLine, Marker::kDisc, 3.0},
                   {"odometry", palette::kOdometry, LegendSymbol::kLine, Marker::kDisc, 3.0},
                   internal::StartLegend(),
                   {"end", palette::kAxis, LegendSymbol::kMarker, Marker::kSquare, 6.0, true},
                   internal::WorldLegend()};
  return header;
}

// A drive's panel title: its label, the distance driven and how far its odometry ends off.
std::string DriveTitle(const OdometryDrive& d, std::size_t i, const std::vector<core::Pose2>& odo) {
  const double length = internal::PathLength(d.truth);
  std::string title = d.label.empty() ? "drive " + std::to_string(i) : d.label;
  if (!d.truth.empty() && !odo.empty()) {
    const double end_error = core::Distance(d.truth.back(), odo.back());
    char buf[160];
    std::snprintf(buf, sizeof(buf), ": %.0f m driven, odometry ends %.1f m off (%.1f%%)", length,
                  end_error, length > 0.0 ? 100.0 * end_error / length : 0.0);
    title += buf;
  }
  return title;
}

// The world, a drive's truth and aligned odometry, its start and where each ends.
void DrawDriveLayers(GlCanvas& c, const OdometryFigureData& data, const OdometryDrive& d,
                     const std::vector<core::Pose2>& odo) {
  internal::DrawWorld(c, data.world);
  c.DrawPolyline(internal::Positions(d.truth), 2.5, palette::kTruth);
  c.DrawPolyline(internal::Positions(odo), 2.5, palette::kOdometry);
  if (!d.truth.empty()) {
    c.DrawMarkers({d.truth.back().translation()}, Marker::kSquare, 11.0, palette::kTruth, 1.5);
    internal::DrawStart(c, d.truth.front().translation());
  }
  if (!odo.empty()) {
    c.DrawMarkers({odo.back().translation()}, Marker::kSquare, 11.0, palette::kOdometry, 1.5);
  }
}

}  // namespace

FigureInfo RenderOdometryFigure(const OdometryFigureData& data, const std::filesystem::path& png,
                                const FigureOptions& options) {
  options.Validate();
  internal::Require(!data.drives.empty(), png, "the odometry figure needs at least one drive");
  const int W = options.width;
  const std::size_t n = data.drives.size();
  const int cols = static_cast<int>(std::min<std::size_t>(n, 2));
  const int rows = static_cast<int>((n + 1) / 2);
  const int tile_w = W / cols;
  const int plot_w = tile_w - internal::kPanelLeft - internal::kPanelRight;

  std::vector<std::vector<core::Pose2>> aligned;
  std::vector<Box2> boxes;
  double aspect = 0.5;
  for (const auto& d : data.drives) {
    aligned.push_back(AlignedOdometry(d));
    Box2 b;
    for (const auto& p : d.truth) b.Extend(p.translation());
    for (const auto& p : aligned.back()) b.Extend(p.translation());
    boxes.push_back(internal::WorldViewBox(b, data.world));
    const Vec2 s = boxes.back().Size();
    if (s.x() > 1e-9) aspect = std::max(aspect, s.y() / s.x());
  }
  const int plot_h = static_cast<int>(std::lround(plot_w * std::min(aspect, 1.1)));

  const internal::Header header = OdometryHeader(options);
  const int top = internal::HeaderHeight(header, W);
  const int tile_h = internal::MapPanelAt(0, 0, tile_w, plot_h).tile.height;
  cv::Mat fig = internal::NewFigure(W, top + rows * tile_h + 8);
  internal::DrawHeader(fig, header);

  std::vector<PanelInfo> panels;
  for (std::size_t i = 0; i < n; ++i) {
    const OdometryDrive& d = data.drives[i];
    const auto& odo = aligned[i];
    const int col = static_cast<int>(i) % cols;
    const int row = static_cast<int>(i) / cols;
    panels.push_back(internal::RenderMapPanel(
        fig, internal::MapPanelAt(col * tile_w, top + row * tile_h, tile_w, plot_h), boxes[i],
        "drive" + std::to_string(i), DriveTitle(d, i, odo), options.supersample,
        [&](GlCanvas& c) { DrawDriveLayers(c, data, d, odo); }));
  }
  return internal::FinishFigure(fig, png, std::move(panels));
}

}  // namespace retrace::viz
