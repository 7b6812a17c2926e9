#include "viz/internal/snapshot_layers.hpp"

#include <algorithm>
#include <cmath>

namespace retrace::viz::internal {

std::vector<Rgba> ParticleColors(const std::vector<double>& weights, std::size_t n) {
  std::vector<Rgba> colors(n, palette::kParticle.WithAlpha(150));
  if (weights.size() != n || n == 0) return colors;
  double w_max = 0.0;
  for (double w : weights) {
    if (std::isfinite(w)) w_max = std::max(w_max, w);
  }
  if (!(w_max > 0.0)) return colors;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = std::isfinite(weights[i]) ? std::clamp(weights[i] / w_max, 0.0, 1.0) : 0.0;
    // Light particles stay faintly visible; heavy ones opaque.
    colors[i] =
        palette::kParticle.WithAlpha(static_cast<std::uint8_t>(std::lround(50.0 + 205.0 * t)));
  }
  return colors;
}

void DrawLocalizationLayers(GlCanvas& c, const LocalizationLayers& l, double scale) {
  c.DrawGrid(l.grid, core::Pose2::Identity());
  std::vector<Vec2> path_points;
  path_points.reserve(l.path.size());
  for (const auto& p : l.path) path_points.push_back(p.translation());
  c.DrawPolyline(path_points, 2.0 * scale, palette::kTaughtPath.WithAlpha(150));
  for (const Circle& p : l.pedestrians) {
    c.FillDisc(p.center, p.radius, palette::kPedestrian.WithAlpha(90));
    c.DrawCircle(p.center, p.radius, 1.5 * scale, palette::kPedestrian);
  }
  std::vector<Vec2> used;
  std::vector<Vec2> rejected;
  std::vector<Vec2> pedestrian_hits;
  for (const ScanPoint& s : l.scan) {
    (s.rejected ? rejected : used).push_back(s.point);
    if (s.hits_pedestrian) pedestrian_hits.push_back(s.point);
  }
  // A purple ring around every point that truly hit a pedestrian, under the point itself.
  c.DrawMarkers(pedestrian_hits, Marker::kDisc, 10.0 * scale, palette::kPedestrian);
  c.DrawMarkers(used, Marker::kDisc, 4.5 * scale, palette::kStaticPoint);
  c.DrawMarkers(rejected, Marker::kDisc, 5.0 * scale, palette::kRejectedPoint);
  c.DrawPoseArrows(l.particles, 11.0 * scale, palette::kParticle,
                   ParticleColors(l.weights, l.particles.size()));
  c.DrawCircle(l.truth.translation(), l.robot_radius, 2.0 * scale, palette::kTruth);
  c.DrawPoseArrows({l.truth}, 22.0 * scale, palette::kTruth, {}, 1.2, palette::kBackground);
  c.DrawPoseArrows({l.estimate}, 22.0 * scale, palette::kEstimate, {}, 1.2, palette::kBackground);
}

std::vector<LegendEntry> LocalizationLegend() {
  return {
      {"taught path", palette::kTaughtPath, LegendSymbol::kLine, Marker::kDisc, 2.0},
      {"scan point", palette::kStaticPoint, LegendSymbol::kMarker, Marker::kDisc, 4.0},
      {"rejected as dynamic", palette::kRejectedPoint, LegendSymbol::kMarker, Marker::kDisc, 4.0},
      {"hit a pedestrian (truth)", palette::kPedestrian, LegendSymbol::kRing},
      {"pedestrian", palette::kPedestrian.WithAlpha(255), LegendSymbol::kMarker, Marker::kDisc,
       7.0},
      {"particles", palette::kParticle, LegendSymbol::kArrow},
      {"estimate", palette::kEstimate, LegendSymbol::kArrow},
      {"ground truth", palette::kTruth, LegendSymbol::kArrow}};
}

}  // namespace retrace::viz::internal
