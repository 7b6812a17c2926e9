#pragma once
// The localization layers of snapshot.png, shared with video frames (private to viz).

#include <vector>

#include "viz/figure_data.hpp"
#include "viz/gl_canvas.hpp"
#include "viz/internal/annotate.hpp"

namespace retrace::viz::internal {

/// Particle colours with opacity growing with weight (equal weights: one opacity).
std::vector<Rgba> ParticleColors(const std::vector<double>& weights, std::size_t n);

/// What the localization layers show, all in M (references to the caller's data, not copies).
struct LocalizationLayers {
  const core::OccupancyGrid& grid;
  const std::vector<core::Pose2>& path;  ///< taught path (may be empty)
  const std::vector<core::Pose2>& particles;
  const std::vector<double>& weights;  ///< one per particle or empty
  const core::Pose2& estimate;
  const core::Pose2& truth;
  const std::vector<ScanPoint>& scan;
  const std::vector<Circle>& pedestrians;
  double robot_radius = 0.0;  ///< m
};

/// Map, taught path (if any), pedestrians, scan points (used / rejected / pedestrian truth),
/// particles, truth with its footprint and the estimate; `scale` multiplies marker sizes.
void DrawLocalizationLayers(GlCanvas& c, const LocalizationLayers& l, double scale);

/// The legend of those layers.
std::vector<LegendEntry> LocalizationLegend();

}  // namespace retrace::viz::internal
