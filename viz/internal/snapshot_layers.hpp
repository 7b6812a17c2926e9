#pragma once
// The localization layers of snapshot.png, shared with video frames (private to viz).

#include <vector>

#include "viz/figure_data.hpp"
#include "viz/gl_canvas.hpp"
#include "viz/internal/annotate.hpp"

namespace retrace::viz::internal {

/// Particle colours with opacity growing with weight (equal weights: one opacity).
std::vector<Rgba> ParticleColors(const std::vector<double>& weights, std::size_t n);

/// Map, taught path (if any), pedestrians, scan points (used / rejected / pedestrian truth),
/// particles, truth with its footprint and the estimate, all in M; `scale` multiplies marker
/// sizes.
void DrawLocalizationLayers(GlCanvas& c, const core::OccupancyGrid& grid,
                            const std::vector<core::Pose2>& path,
                            const std::vector<core::Pose2>& particles,
                            const std::vector<double>& weights, const core::Pose2& estimate,
                            const core::Pose2& truth, const std::vector<ScanPoint>& scan,
                            const std::vector<Circle>& pedestrians, double robot_radius,
                            double scale);

/// The legend of those layers.
std::vector<LegendEntry> LocalizationLegend();

}  // namespace retrace::viz::internal
