#pragma once
// World files (worlds/*.yaml): the static geometry of a simulated world in frame W and its
// pedestrian groups. All lengths in m, angles in rad. Example:
//
//   name: office
//   boxes:     [{center: [5, 0], size: [2, 1], yaw: 0.3}]
//   circles:   [{center: [1, 1], radius: 0.15}]
//   polygons:  [{points: [[0, 0], [1, 0], [0, 1]]}]
//   walls:     [{points: [[0, 0], [10, 0], [10, 8]], thickness: 0.15, closed: false}]
//   maps:      [{file: floor.yaml, occupied_threshold: 0.65}]   # ROS map_server maps
//   pedestrians: [{count: 5, region_min: [0, 0], region_max: [10, 8], mode: wander}]

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "io/config_override.hpp"
#include "sim/pedestrian_config.hpp"
#include "sim/static_geometry.hpp"

namespace retrace::sim {

struct BoxConfig {
  core::Vec2 center{0.0, 0.0};
  core::Vec2 size{1.0, 1.0};  ///< full extents along the box's own x and y (m)
  double yaw = 0.0;           ///< rad
  template <class V>
  void Reflect(V& v) {
    v("center", center);
    v("size", size);
    v("yaw", yaw);
  }
  /// Throws core::ConfigError naming the key: finite centre and yaw, positive finite size.
  void Validate() const;
};

/// The corners of a box in W (m), counter-clockwise.
std::vector<core::Vec2> BoxRing(const BoxConfig& box);

struct CircleConfig {
  core::Vec2 center{0.0, 0.0};
  double radius = 0.1;
  template <class V>
  void Reflect(V& v) {
    v("center", center);
    v("radius", radius);
  }
  /// Throws core::ConfigError naming the key: finite centre, positive finite radius.
  void Validate() const;
};

/// A solid simple polygon (either winding, first point not repeated).
struct PolygonConfig {
  std::vector<core::Vec2> points;
  template <class V>
  void Reflect(V& v) {
    v("points", points);
  }
  void Validate() const;
};

/// A thick polyline (walls, hedges, curbs): each piece is a solid rectangle of the given
/// thickness, extended by half the thickness at both ends so that corners are closed.
struct WallConfig {
  std::vector<core::Vec2> points;
  double thickness = 0.1;
  bool closed = false;
  template <class V>
  void Reflect(V& v) {
    v("points", points);
    v("thickness", thickness);
    v("closed", closed);
  }
  void Validate() const;
};

/// An imported ROS map_server map; cells with p ≥ occupied_threshold become solid. The map's
/// own origin places it in W.
struct MapImportConfig {
  std::string file;  ///< relative to the world file's folder
  double occupied_threshold = 0.65;
  /// What the world holds in the map's unknown cells (neither occupied nor known free): 0
  /// (default) leaves them open; otherwise the mean distance (m) a ray travels through unknown
  /// cells before it meets something. Each unknown cell becomes solid with probability
  /// 1 − exp(−π r / (4 ℓ)) for resolution r (a ray in a uniformly random direction crosses 4/(π r)
  /// cells per metre), drawn from `unknown_seed` (docs/METHOD.md, "What the map does not hold").
  double unknown_free_path = 0.0;
  std::uint64_t unknown_seed = 1;
  template <class V>
  void Reflect(V& v) {
    v("file", file);
    v("occupied_threshold", occupied_threshold);
    v("unknown_free_path", unknown_free_path);
    v("unknown_seed", unknown_seed);
  }
  void Validate() const;
};

struct WorldConfig {
  std::string name;
  std::vector<BoxConfig> boxes;
  std::vector<CircleConfig> circles;
  std::vector<PolygonConfig> polygons;
  std::vector<WallConfig> walls;
  std::vector<MapImportConfig> maps;
  std::vector<PedestrianGroupConfig> pedestrians;
  template <class V>
  void Reflect(V& v) {
    v("name", name);
    v("boxes", boxes);
    v("circles", circles);
    v("polygons", polygons);
    v("walls", walls);
    v("maps", maps);
    v("pedestrians", pedestrians);
  }
};

/// A loaded world: its config and the static geometry built from it.
struct World {
  WorldConfig config;
  std::filesystem::path source;  ///< the world file (for messages and relative paths)
  StaticGeometry geometry;
};

/// Builds the static geometry. Map files are resolved relative to `base_dir`.
/// Throws core::WorldError if the world has no geometry, core::IoError/ConfigError on a bad map.
StaticGeometry BuildGeometry(const WorldConfig& config, const std::filesystem::path& base_dir);

/// Adds an occupancy grid's solid cells (at `map`'s threshold, its unknown cells filled as
/// `map` says; `map.file` only names it in errors) to *geometry. Throws core::WorldError for a
/// grid without solid cells.
void AddMapGeometry(const core::OccupancyGrid& grid, const MapImportConfig& map,
                    StaticGeometry* geometry);

/// Loads a world file strictly (unknown keys, NaN, negative sizes are ConfigErrors naming file,
/// line and key), applies overrides and builds its geometry.
World LoadWorld(const std::filesystem::path& file,
                const std::vector<io::ConfigOverride>& overrides = {});

}  // namespace retrace::sim
