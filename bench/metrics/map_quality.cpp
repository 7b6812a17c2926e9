#include "bench/metrics/map_quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/occupancy_grid.hpp"
#include "sim/geometry_index.hpp"

namespace retrace::bench {

core::Pose2 AlignPoints(const std::vector<core::Vec2>& a, const std::vector<core::Vec2>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  if (n == 0) return core::Pose2::Identity();
  core::Vec2 ca = core::Vec2::Zero();
  core::Vec2 cb = core::Vec2::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    ca += a[i];
    cb += b[i];
  }
  ca /= static_cast<double>(n);
  cb /= static_cast<double>(n);
  // The rotation maximising Σ (b_i − cb)·R(a_i − ca): θ = atan2(Σ cross, Σ dot).
  double dot = 0.0;
  double cross = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const core::Vec2 p = a[i] - ca;
    const core::Vec2 q = b[i] - cb;
    dot += p.dot(q);
    cross += p.x() * q.y() - p.y() * q.x();
  }
  const double theta = (dot == 0.0 && cross == 0.0) ? 0.0 : std::atan2(cross, dot);
  const core::Pose2 R(0.0, 0.0, theta);
  const core::Vec2 t = cb - R * ca;
  return core::Pose2(t.x(), t.y(), theta);
}

MapQualityStats ComputeMapQuality(const ModeTeach& teach, const sim::StaticGeometry& world,
                                  double occupied_threshold) {
  MapQualityStats stats;
  const sim::GeometryIndex index(world);
  const float occupied_log_odds = static_cast<float>(core::Logit(occupied_threshold));
  double squared_sum = 0.0;
  long long samples = 0;
  long long occupied = 0;
  long long agreeing = 0;
  const std::size_t n_maps = std::min(teach.bundle.maps.size(), teach.trace.maps.size());
  for (std::size_t k = 0; k < n_maps; ++k) {
    const TeachMapTrace& trace = teach.trace.maps[k];
    std::vector<core::Vec2> in_map;
    std::vector<core::Vec2> in_world;
    for (std::size_t i = 0; i < std::min(trace.X_MR.size(), trace.X_WR.size()); ++i) {
      in_map.push_back(trace.X_MR[i].translation());
      in_world.push_back(trace.X_WR[i].translation());
    }
    MapQuality q;
    q.X_WM = AlignPoints(in_map, in_world);
    q.samples = static_cast<int>(in_map.size());
    double sum = 0.0;
    for (std::size_t i = 0; i < in_map.size(); ++i)
      sum += (q.X_WM * in_map[i] - in_world[i]).squaredNorm();
    q.distortion_m = in_map.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(in_map.size()));
    squared_sum += sum;
    samples += q.samples;

    const core::OccupancyGrid& grid = teach.bundle.maps[k].grid;
    const double tolerance = grid.resolution();
    for (int y = 0; y < grid.height(); ++y) {
      for (int x = 0; x < grid.width(); ++x) {
        if (grid.LogOdds({x, y}) < occupied_log_odds) continue;
        ++q.occupied_cells;
        const core::Vec2 c_W = q.X_WM * grid.CellToWorld({x, y});
        if (index.Clearance(c_W, 2.0 * tolerance) <= tolerance) ++q.agreeing_cells;
      }
    }
    occupied += q.occupied_cells;
    agreeing += q.agreeing_cells;
    stats.distortion_max_m = std::max(stats.distortion_max_m, q.distortion_m);
    stats.maps.push_back(q);
  }
  stats.distortion_rms_m =
      samples > 0 ? std::sqrt(squared_sum / static_cast<double>(samples)) : 0.0;
  stats.agreement = occupied > 0 ? static_cast<double>(agreeing) / static_cast<double>(occupied)
                                 : std::numeric_limits<double>::quiet_NaN();
  return stats;
}

}  // namespace retrace::bench
