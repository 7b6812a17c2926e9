#include "sim/grid_edges.hpp"

#include <cmath>
#include <numbers>

#include "io/ros_map.hpp"

namespace retrace::sim {

OccupancyMask OccupiedMask(const core::OccupancyGrid& grid, double occupied_threshold) {
  OccupancyMask mask;
  mask.width = grid.width();
  mask.height = grid.height();
  mask.resolution = grid.resolution();
  mask.origin = grid.origin();
  mask.occupied.resize(grid.log_odds().size());
  // Compare in log-odds: avoids an exp() per cell on 4-million-cell maps.
  const float threshold = static_cast<float>(core::Logit(occupied_threshold));
  for (std::size_t i = 0; i < mask.occupied.size(); ++i) {
    mask.occupied[i] = grid.log_odds()[i] >= threshold ? 1 : 0;
  }
  return mask;
}

void FillUnknownCells(const core::OccupancyGrid& grid, double occupied_threshold, double free_path,
                      core::Rng rng, OccupancyMask* mask) {
  const double p = -std::expm1(-std::numbers::pi * grid.resolution() / (4.0 * free_path));
  const float occupied = static_cast<float>(core::Logit(occupied_threshold));
  const float known_free = static_cast<float>(core::Logit(io::kRosMapKnownFreeBelow));
  for (std::size_t i = 0; i < mask->occupied.size(); ++i) {
    const float l = grid.log_odds()[i];
    if (l < known_free || l >= occupied) continue;
    if (rng.Bernoulli(p)) mask->occupied[i] = 1;
  }
}

std::vector<Segment> MergedBoundaryEdges(const OccupancyMask& mask) {
  const int w = mask.width;
  const int h = mask.height;
  auto solid = [&](int x, int y) {
    if (x < 0 || y < 0 || x >= w || y >= h) return false;
    return mask.occupied[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                         static_cast<std::size_t>(x)] != 0;
  };
  const double r = mask.resolution;
  const Vec2 o = mask.origin;
  std::vector<Segment> edges;
  // Horizontal faces lie on the line between rows y-1 and y; a face at column x exists where
  // exactly one of the two cells is solid. Consecutive faces merge into one edge.
  for (int y = 0; y <= h; ++y) {
    int run_start = -1;
    for (int x = 0; x <= w; ++x) {
      const bool face = x < w && solid(x, y - 1) != solid(x, y);
      if (face && run_start < 0) run_start = x;
      if (!face && run_start >= 0) {
        edges.push_back({o + Vec2(run_start * r, y * r), o + Vec2(x * r, y * r)});
        run_start = -1;
      }
    }
  }
  for (int x = 0; x <= w; ++x) {
    int run_start = -1;
    for (int y = 0; y <= h; ++y) {
      const bool face = y < h && solid(x - 1, y) != solid(x, y);
      if (face && run_start < 0) run_start = y;
      if (!face && run_start >= 0) {
        edges.push_back({o + Vec2(x * r, run_start * r), o + Vec2(x * r, y * r)});
        run_start = -1;
      }
    }
  }
  return edges;
}

}  // namespace retrace::sim
