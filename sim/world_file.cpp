#include "sim/world_file.hpp"

#include <cmath>

#include "core/errors.hpp"
#include "core/limits.hpp"
#include "io/config_yaml.hpp"
#include "io/ros_map.hpp"
#include "sim/grid_edges.hpp"

namespace retrace::sim {
namespace {

double SignedArea(const std::vector<Vec2>& ring) {
  double a = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec2& p = ring[i];
    const Vec2& q = ring[(i + 1) % ring.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

void AddWall(const WallConfig& wall, StaticGeometry* geometry) {
  const std::size_t n = wall.points.size();
  const std::size_t pieces = wall.closed ? n : n - 1;
  const double h = 0.5 * wall.thickness;
  for (std::size_t i = 0; i < pieces; ++i) {
    const Vec2& a = wall.points[i];
    const Vec2& b = wall.points[(i + 1) % n];
    const Vec2 d = (b - a).normalized();
    const Vec2 nrm(-d.y(), d.x());
    const Vec2 a0 = a - h * d;
    const Vec2 b0 = b + h * d;
    geometry->AddPolygon({a0 - h * nrm, b0 - h * nrm, b0 + h * nrm, a0 + h * nrm});
  }
}

}  // namespace

std::vector<Vec2> BoxRing(const BoxConfig& b) {
  const core::Pose2 X_WB(b.center.x(), b.center.y(), b.yaw);
  const double hx = 0.5 * b.size.x();
  const double hy = 0.5 * b.size.y();
  return {X_WB * Vec2(-hx, -hy), X_WB * Vec2(hx, -hy), X_WB * Vec2(hx, hy), X_WB * Vec2(-hx, hy)};
}

void BoxConfig::Validate() const {
  core::RequirePoint("center", center);
  core::RequireWorldLength("size", size.x());
  core::RequireWorldLength("size", size.y());
  core::RequireFinite("yaw", yaw);
}

void CircleConfig::Validate() const {
  core::RequirePoint("center", center);
  core::RequireWorldLength("radius", radius);
}

void PolygonConfig::Validate() const {
  if (points.size() < 3) {
    throw core::ConfigError(
        "points", "a polygon needs at least 3 points, got " + std::to_string(points.size()));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    core::RequirePoint("points[" + std::to_string(i) + "]", points[i]);
  }
  if (std::abs(SignedArea(points)) < 1e-9)
    throw core::ConfigError("points", "polygon has zero area");
}

void WallConfig::Validate() const {
  if (points.size() < 2) {
    throw core::ConfigError("points",
                            "a wall needs at least 2 points, got " + std::to_string(points.size()));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    core::RequirePoint("points[" + std::to_string(i) + "]", points[i]);
  }
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    if ((points[i + 1] - points[i]).norm() < 1e-9) {
      throw core::ConfigError(
          "points", "points " + std::to_string(i) + " and " + std::to_string(i + 1) + " coincide");
    }
  }
  core::RequireWorldLength("thickness", thickness);
}

void MapImportConfig::Validate() const {
  if (file.empty()) throw core::ConfigError("file", "must name a ROS map YAML file");
  core::RequireInRange("occupied_threshold", occupied_threshold, 0.0, 1.0);
  if (!(unknown_free_path >= 0.0) || !std::isfinite(unknown_free_path)) {
    throw core::ConfigError("unknown_free_path",
                            "must be 0 (unknown cells open) or a distance in m, not " +
                                core::FormatNumber(unknown_free_path));
  }
}

void AddMapGeometry(const core::OccupancyGrid& grid, const MapImportConfig& map,
                    StaticGeometry* geometry) {
  OccupancyMask mask = OccupiedMask(grid, map.occupied_threshold);
  if (map.unknown_free_path > 0.0) {
    FillUnknownCells(grid, map.occupied_threshold, map.unknown_free_path,
                     core::Rng(map.unknown_seed).Split("unknown cells"), &mask);
  }
  const std::vector<Segment> edges = MergedBoundaryEdges(mask);
  if (edges.empty()) {
    throw core::WorldError(map.file + ": the map has no occupied cells (threshold " +
                           core::FormatNumber(map.occupied_threshold) + ")");
  }
  geometry->AddEdges(edges, std::move(mask));
}

StaticGeometry BuildGeometry(const WorldConfig& config, const std::filesystem::path& base_dir) {
  StaticGeometry geometry;
  for (const auto& b : config.boxes) geometry.AddPolygon(BoxRing(b));
  for (const auto& c : config.circles) geometry.AddCircle({c.center, c.radius});
  for (const auto& p : config.polygons) geometry.AddPolygon(p.points);
  for (const auto& w : config.walls) AddWall(w, &geometry);
  for (const auto& m : config.maps) {
    MapImportConfig named = m;
    named.file = (base_dir / m.file).string();
    AddMapGeometry(io::ReadRosMap(named.file), named, &geometry);
  }
  if (geometry.empty()) {
    throw core::WorldError(
        "the world has no static geometry: add boxes, circles, polygons, "
        "walls or maps");
  }
  return geometry;
}

World LoadWorld(const std::filesystem::path& file,
                const std::vector<io::ConfigOverride>& overrides) {
  World world;
  world.source = file;
  world.config = io::LoadConfigFile<WorldConfig>(file, overrides);
  try {
    world.geometry = BuildGeometry(world.config, file.parent_path());
  } catch (const core::WorldError& e) {
    throw core::WorldError(file.string() + ": " + e.what());
  }
  return world;
}

}  // namespace retrace::sim
