#pragma once
// How good the taught maps are, for every map mode, against ground truth: each map is aligned
// to the world with the rigid transform that best fits its poses to the ground-truth poses of
// the same instants (least squares on positions, Kabsch/Umeyama without scale), then
//   distortion  the RMS of the remaining position residuals (m): how much the map is bent by
//               drift. 0 for a map built from ground truth; a rigid offset costs nothing.
//   agreement   the share of the map's occupied cells whose centre, in W through that
//               transform, lies within one cell of a static surface of the teach world
//               (pedestrians and blur count against it).

#include <vector>

#include "bench/engine/teach_drive.hpp"
#include "core/pose2.hpp"
#include "sim/static_geometry.hpp"

namespace retrace::bench {

struct MapQuality {
  core::Pose2 X_WM;           ///< the best rigid alignment of the map frame to W
  double distortion_m = 0.0;  ///< RMS position residual after the alignment
  int samples = 0;            ///< poses aligned (the map's odometry ticks)
  int occupied_cells = 0;     ///< cells with probability >= occupied_threshold
  int agreeing_cells = 0;     ///< of those, within one cell of a static surface
};

struct MapQualityStats {
  std::vector<MapQuality> maps;   ///< per map of the mode, in order
  double distortion_rms_m = 0.0;  ///< over all maps' residuals pooled
  double distortion_max_m = 0.0;  ///< the worst map's RMS
  double agreement = 0.0;         ///< agreeing / occupied cells, all maps pooled (NaN: none)
};

/// The best rigid transform T (rotation and translation) minimising Σ |T·a_i − b_i|²; the
/// identity rotation when a has fewer than two distinct points.
core::Pose2 AlignPoints(const std::vector<core::Vec2>& a, const std::vector<core::Vec2>& b);

/// The quality of every map of `teach` against the static geometry of the world it was
/// taught in; `occupied_threshold` as the localizer's likelihood field uses it.
MapQualityStats ComputeMapQuality(const ModeTeach& teach, const sim::StaticGeometry& world,
                                  double occupied_threshold);

}  // namespace retrace::bench
