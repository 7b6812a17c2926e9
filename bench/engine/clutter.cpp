#include "bench/engine/clutter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/nearest_grid.hpp"
#include "core/segment.hpp"
#include "sim/geometry_index.hpp"

namespace retrace::bench {
namespace {

constexpr double kCell = 0.2;            // m: the band's area and draws are on cells this wide
constexpr int kMaxMisses = 5000;         // draws in a row that may fail before giving up
constexpr double kStandingMargin = 0.5;  // m more between people and geometry (walk planner)

// Centres of the cells (kCell wide) whose centre lies in (inner, outer] from the route and
// outside every solid: the band's free area, cell by cell, in a fixed order.
std::vector<core::Vec2> BandCells(const ClutterSite& site, double inner, double outer) {
  const std::vector<core::Vec2>& route = *site.route;
  core::Vec2 lo = route.front();
  core::Vec2 hi = route.front();
  for (const core::Vec2& p : route) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  lo -= core::Vec2(outer + kCell, outer + kCell);
  hi += core::Vec2(outer + kCell, outer + kCell);
  const auto nx = static_cast<std::size_t>(std::ceil((hi.x() - lo.x()) / kCell));
  const auto ny = static_cast<std::size_t>(std::ceil((hi.y() - lo.y()) / kCell));
  std::vector<float> distance(nx * ny, std::numeric_limits<float>::infinity());
  auto centre = [&](std::size_t x, std::size_t y) -> core::Vec2 {
    return lo + core::Vec2((static_cast<double>(x) + 0.5) * kCell,
                           (static_cast<double>(y) + 0.5) * kCell);
  };
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    const core::Vec2 a = route[i];
    const core::Vec2 b = route[i + 1];
    const core::Vec2 s_lo = a.cwiseMin(b) - core::Vec2(outer, outer) - lo;
    const core::Vec2 s_hi = a.cwiseMax(b) + core::Vec2(outer, outer) - lo;
    const auto x0 = static_cast<std::size_t>(std::max(0.0, std::floor(s_lo.x() / kCell)));
    const auto y0 = static_cast<std::size_t>(std::max(0.0, std::floor(s_lo.y() / kCell)));
    const std::size_t x1 = std::min(nx, static_cast<std::size_t>(s_hi.x() / kCell) + 1);
    const std::size_t y1 = std::min(ny, static_cast<std::size_t>(s_hi.y() / kCell) + 1);
    for (std::size_t y = y0; y < y1; ++y) {
      for (std::size_t x = x0; x < x1; ++x) {
        const auto d = static_cast<float>(core::SegmentDistance(centre(x, y), a, b));
        distance[y * nx + x] = std::min(distance[y * nx + x], d);
      }
    }
  }
  std::vector<core::Vec2> cells;
  for (std::size_t y = 0; y < ny; ++y) {
    for (std::size_t x = 0; x < nx; ++x) {
      const double d = distance[y * nx + x];
      if (d > inner && d <= outer && !site.geometry->IsInside(centre(x, y))) {
        cells.push_back(centre(x, y));
      }
    }
  }
  return cells;
}

// Draws footprints' centres uniformly over the band's cells and keeps those that fit.
class Placer {
 public:
  Placer(const ClutterConfig& config, const ClutterSite& site, std::vector<core::Vec2> cells)
      : config_(config),
        site_(site),
        corridor_(site.robot_radius + config.clearance),
        cells_(std::move(cells)),
        route_distance_(*site.route),
        index_(*site.geometry, 1.0) {}

  // A free centre for a footprint bounded by a disc of `bound` (m) that keeps `wall_gap` (m)
  // from the geometry; nullopt after kMaxMisses failed draws in a row.
  std::optional<core::Vec2> Place(double bound, double wall_gap, core::Rng& rng) {
    for (int miss = 0; miss < kMaxMisses; ++miss) {
      const core::Vec2 cell = cells_[rng.UniformIndex(cells_.size())];
      const core::Vec2 p =
          cell + core::Vec2(rng.Uniform(-0.5, 0.5) * kCell, rng.Uniform(-0.5, 0.5) * kCell);
      if (Fits(p, bound, wall_gap)) {
        placed_.push_back({p, bound});
        return p;
      }
    }
    return std::nullopt;
  }

 private:
  bool Fits(const core::Vec2& p, double bound, double wall_gap) const {
    const double d = route_distance_(p);
    if (d > config_.band || d - bound < corridor_) return false;
    if ((p - site_.route->front()).norm() < site_.start_clear + bound) return false;
    if (index_.Clearance(p, bound + wall_gap) < bound + wall_gap) return false;
    for (const sim::Circle& c : placed_) {
      const double min_d = c.radius + bound + config_.gap;
      if ((c.center - p).squaredNorm() < min_d * min_d) return false;
    }
    return true;
  }

  const ClutterConfig& config_;
  const ClutterSite& site_;
  double corridor_;
  std::vector<core::Vec2> cells_;
  core::PolylineDistance route_distance_;
  sim::GeometryIndex index_;
  std::vector<sim::Circle> placed_;
};

std::size_t CountFor(double density, double area) {
  return static_cast<std::size_t>(std::llround(density * area));
}

[[noreturn]] void ThrowFull(const char* key, std::size_t placed, std::size_t wanted, double area) {
  throw core::ConfigError(
      key, "only " + std::to_string(placed) + " of " + std::to_string(wanted) +
               " fit beside the route (band area " + core::FormatNumber(std::round(area)) +
               " m², " + std::to_string(kMaxMisses) +
               " draws in a row found no free place): lower the density or widen the band");
}

void PlaceObjects(const ClutterConfig& config, Placer& placer, core::Rng rng, Clutter* out) {
  const std::size_t wanted = CountFor(config.density, out->band_area);
  for (std::size_t i = 0; i < wanted; ++i) {
    const ClutterKind kind = config.kinds[rng.UniformIndex(config.kinds.size())];
    const ClutterFootprint foot = FootprintOf(kind);
    const double yaw = rng.Uniform(-core::kPi, core::kPi);
    const std::optional<core::Vec2> p = placer.Place(foot.Bound(), config.gap, rng);
    if (!p) ThrowFull("density", i, wanted, out->band_area);
    if (foot.radius > 0.0) {
      out->circles.push_back({*p, foot.radius});
    } else {
      out->boxes.push_back({*p, foot.size, yaw});
    }
  }
}

void PlacePeople(const ClutterConfig& config, Placer& placer, core::Rng rng, Clutter* out) {
  const std::size_t wanted = CountFor(config.standing_density, out->band_area);
  for (std::size_t i = 0; i < wanted; ++i) {
    const std::optional<core::Vec2> p =
        placer.Place(config.person_radius, config.gap + kStandingMargin, rng);
    if (!p) ThrowFull("standing_density", i, wanted, out->band_area);
    out->standing.push_back(*p);
  }
}

}  // namespace

void ClutterConfig::Validate() const {
  core::RequireInRange("density", density, 0.0, 1.0);
  core::RequireInRange("standing_density", standing_density, 0.0, 1.0);
  core::RequirePositive("band", band);
  core::RequireNonNegative("clearance", clearance);
  core::RequireNonNegative("gap", gap);
  core::RequireInRange("person_radius", person_radius, 0.1, 0.5);
  if (kinds.empty()) throw core::ConfigError("kinds", "must list at least one kind");
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (kinds[i] == kinds[j]) {
        throw core::ConfigError("kinds",
                                "lists '" + std::string(core::EnumName(kinds[i])) + "' twice");
      }
    }
  }
}

ClutterFootprint FootprintOf(ClutterKind kind) {
  switch (kind) {
    case ClutterKind::kChair:
      return {{0.5, 0.5}, 0.0};
    case ClutterKind::kBin:
      return {{0.0, 0.0}, 0.2};
    case ClutterKind::kBike:
      return {{1.8, 0.6}, 0.0};
    case ClutterKind::kBox:
      return {{0.6, 0.6}, 0.0};
  }
  return {{0.5, 0.5}, 0.0};
}

double MeanClutterWidth(const ClutterConfig& config) {
  double sum = 0.0;
  for (const ClutterKind kind : config.kinds) {
    const ClutterFootprint f = FootprintOf(kind);
    sum += f.radius > 0.0 ? 2.0 * f.radius : 2.0 * (f.size.x() + f.size.y()) / std::numbers::pi;
  }
  return config.kinds.empty() ? 0.0 : sum / static_cast<double>(config.kinds.size());
}

double CalibratedClutterDensity(const ClutterConfig& config) {
  return kCalibratedBlockingRate / MeanClutterWidth(config);
}

Clutter GenerateClutter(const ClutterConfig& config, const ClutterSite& site,
                        const core::Rng& rng) {
  Clutter out;
  if (!config.enabled()) return out;
  std::vector<core::Vec2> cells =
      BandCells(site, site.robot_radius + config.clearance, config.band);
  out.band_area = static_cast<double>(cells.size()) * kCell * kCell;
  if (cells.empty()) {
    throw core::ConfigError("band", "leaves no free area beside the route outside the corridor (" +
                                        core::FormatNumber(site.robot_radius + config.clearance) +
                                        " m either side)");
  }
  Placer placer(config, site, std::move(cells));
  PlaceObjects(config, placer, rng.Split("objects"), &out);
  PlacePeople(config, placer, rng.Split("standing"), &out);
  return out;
}

std::vector<sim::PedestrianGroupConfig> StandingGroups(const Clutter& clutter,
                                                       double person_radius) {
  std::vector<sim::PedestrianGroupConfig> groups;
  for (const core::Vec2& p : clutter.standing) {
    sim::PedestrianGroupConfig g;
    g.count = 1;
    g.region_min = p - core::Vec2(0.01, 0.01);
    g.region_max = p + core::Vec2(0.01, 0.01);
    g.mode = sim::PedestrianMode::kStand;
    g.radius = person_radius;
    groups.push_back(g);
  }
  return groups;
}

}  // namespace retrace::bench
