#include "bench/calibration/unmapped_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/nearest_grid.hpp"
#include "io/ros_map.hpp"

namespace retrace::bench {

namespace {

// True when every cell within `cells` (a square) of c is known free.
bool ClearOfWalls(const core::OccupancyGrid& grid, float known_free, core::CellIndex c, int cells) {
  for (int y = c.y - cells; y <= c.y + cells; ++y) {
    for (int x = c.x - cells; x <= c.x + cells; ++x) {
      if (!grid.Contains({x, y}) || grid.LogOdds({x, y}) >= known_free) return false;
    }
  }
  return true;
}

}  // namespace

UnmappedMap::UnmappedMap(const core::OccupancyGrid& grid, double occupied_threshold,
                         std::span<const core::Vec2> route, const ClutterConfig& clutter,
                         double robot_radius)
    : grid_(grid), kinds_(grid.log_odds().size(), kOpen) {
  const float occupied = static_cast<float>(core::Logit(occupied_threshold));
  const float known_free = static_cast<float>(core::Logit(io::kRosMapKnownFreeBelow));
  const core::PolylineDistance to_route(std::vector<core::Vec2>(route.begin(), route.end()));
  const double corridor = robot_radius + clutter.clearance;
  // Objects keep clutter.gap from walls and unknown cells; readings ending nearer them are
  // mostly the map's walls a cell off, not objects.
  const int wall_cells = static_cast<int>(std::ceil(clutter.gap / grid.resolution() - 1e-9));
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const std::size_t i = grid.Index({x, y});
      const float l = grid.log_odds()[i];
      if (l >= occupied) continue;
      if (l >= known_free) {
        kinds_[i] = kUnknownCell;
        continue;
      }
      const double d = to_route(grid.CellToWorld({x, y}));
      if (d > corridor && d <= clutter.band && ClearOfWalls(grid, known_free, {x, y}, wall_cells))
        kinds_[i] = kBandCell;
    }
  }
}

UnmappedMap::Kind UnmappedMap::KindAt(core::CellIndex c) const {
  return grid_.Contains(c) ? static_cast<Kind>(kinds_[grid_.Index(c)]) : kOpen;
}

BandObservations UnmappedMap::NewObservations() const {
  return {std::vector<std::uint32_t>(kinds_.size(), 0),
          std::vector<std::uint32_t>(kinds_.size(), 0)};
}

void UnmappedMap::MarkStaticHits(const BandObservations& observations,
                                 std::span<UnmappedBeam> beams) const {
  const auto stays = [&](int x, int y) {
    if (!grid_.Contains({x, y})) return false;
    const std::size_t i = grid_.Index({x, y});
    const std::uint32_t hits = observations.hits[i];
    return hits >= 2 && hits >= observations.passes[i];
  };
  for (UnmappedBeam& b : beams) {
    if (b.end != BeamEnd::kBand) continue;
    const int x0 = static_cast<int>(b.end_cell % static_cast<std::uint32_t>(grid_.width()));
    const int y0 = static_cast<int>(b.end_cell / static_cast<std::uint32_t>(grid_.width()));
    for (int y = y0 - 1; y <= y0 + 1 && !b.end_static; ++y)
      for (int x = x0 - 1; x <= x0 + 1 && !b.end_static; ++x) b.end_static = stays(x, y);
  }
}

UnmappedBeam UnmappedMap::Walk(double t, const core::Vec2& origin, const core::Vec2& dir,
                               double reading, double map_range,
                               BandObservations* observations) const {
  UnmappedBeam beam{t, reading, map_range};
  const double length = std::min(reading, map_range);
  // Amanatides & Woo's traversal: the ray's parameter at each cell's exit, adding the length
  // inside each cell to its kind.
  const double r = grid_.resolution();
  const core::Vec2 p = (origin - grid_.origin()) / r;
  int x = static_cast<int>(std::floor(p.x()));
  int y = static_cast<int>(std::floor(p.y()));
  const int step_x = dir.x() >= 0.0 ? 1 : -1;
  const int step_y = dir.y() >= 0.0 ? 1 : -1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double delta_x = dir.x() != 0.0 ? r / std::abs(dir.x()) : kInf;
  const double delta_y = dir.y() != 0.0 ? r / std::abs(dir.y()) : kInf;
  double next_x = dir.x() != 0.0 ? (step_x > 0 ? x + 1 - p.x() : p.x() - x) * delta_x : kInf;
  double next_y = dir.y() != 0.0 ? (step_y > 0 ? y + 1 - p.y() : p.y() - y) * delta_y : kInf;
  double entered = 0.0;
  while (entered < length) {
    const double exit = std::min({next_x, next_y, length});
    const Kind kind = KindAt({x, y});
    if (kind == kUnknownCell) beam.unknown_m += static_cast<float>(exit - entered);
    if (kind == kBandCell) {
      beam.band_m += static_cast<float>(exit - entered);
      if (exit < length) ++observations->passes[grid_.Index({x, y})];
    }
    entered = exit;
    if (next_x < next_y) {
      x += step_x;
      next_x += delta_x;
    } else {
      y += step_y;
      next_y += delta_y;
    }
  }
  if (reading < map_range) {
    const core::CellIndex end = grid_.WorldToCell(origin + reading * dir);
    const Kind kind = KindAt(end);
    beam.end = kind == kUnknownCell ? BeamEnd::kUnknown
               : kind == kBandCell  ? BeamEnd::kBand
                                    : BeamEnd::kOther;
    if (kind == kBandCell) {
      beam.end_cell = static_cast<std::uint32_t>(grid_.Index(end));
      ++observations->hits[beam.end_cell];
    }
  }
  return beam;
}

std::vector<core::Vec2> RouteInMap(const std::vector<io::StampedPose>& reference,
                                   const core::Pose2& X_MW, double from_stamp, double to_stamp) {
  constexpr double kSpacing = 0.1;  // m
  std::vector<core::Vec2> route;
  for (const io::StampedPose& p : reference) {
    if (p.t < from_stamp || p.t > to_stamp) continue;
    const core::Vec2 q = (X_MW * p.pose).translation();
    if (route.empty() || (q - route.back()).norm() >= kSpacing) route.push_back(q);
  }
  return route;
}

core::OccupancyGrid ClearedAlongRoute(core::OccupancyGrid grid,
                                      const std::vector<core::Vec2>& route,
                                      const ClutterConfig& clutter) {
  const double radius = ClutterSite{}.robot_radius + clutter.clearance;
  const float known_free = static_cast<float>(core::Logit(io::kRosMapKnownFreeBelow));
  const float unknown_below = static_cast<float>(core::Logit(0.5));
  const core::PolylineDistance to_route(route);
  const int reach = static_cast<int>(std::ceil(radius / grid.resolution()));
  // Only cells near a route point can be within the radius of the route.
  std::vector<std::uint8_t> near(grid.log_odds().size(), 0);
  for (const core::Vec2& p : route) {
    const core::CellIndex c = grid.WorldToCell(p);
    for (int y = c.y - reach; y <= c.y + reach; ++y)
      for (int x = c.x - reach; x <= c.x + reach; ++x)
        if (grid.Contains({x, y})) near[grid.Index({x, y})] = 1;
  }
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const float l = grid.LogOdds({x, y});
      if (!near[grid.Index({x, y})] || l < known_free || l > unknown_below) continue;
      if (to_route(grid.CellToWorld({x, y})) <= radius)
        grid.SetProbability({x, y}, io::kRosMapFreeProbability);
    }
  }
  return grid;
}

UnmappedFit FitUnmapped(std::span<const UnmappedBeam> beams, double margin, double far_margin,
                        double mean_width) {
  UnmappedFit fit;
  fit.mean_width_m = mean_width;
  for (const UnmappedBeam& b : beams) {
    ++fit.beams;
    // A return from beyond the map's first wall: a random reading, or the map wrong there (a
    // door open, glass); it says nothing about what the ray passed. No return counts: the ray
    // passed everything up to the map's range (outdoors, open sky), or the sensor dropped it,
    // which the simulated sensor does as often (indirect inference).
    if (std::isfinite(b.reading) && b.reading > b.map_range + far_margin) {
      ++fit.unexplained;
      continue;
    }
    fit.unknown_exposure_m += b.unknown_m;
    fit.band_exposure_m += b.band_m;
    if (!(b.reading < b.map_range - margin)) continue;
    ++fit.short_readings;
    if (b.end == BeamEnd::kUnknown) ++fit.unknown_hits;
    if (b.end == BeamEnd::kBand) ++fit.band_hits;
    if (b.end == BeamEnd::kBand && b.end_static) ++fit.static_band_hits;
  }
  if (fit.unknown_hits > 0)
    fit.unknown_free_path = fit.unknown_exposure_m / static_cast<double>(fit.unknown_hits);
  if (fit.band_exposure_m > 0.0 && mean_width > 0.0)
    fit.density = static_cast<double>(fit.static_band_hits) / (fit.band_exposure_m * mean_width);
  return fit;
}

}  // namespace retrace::bench
