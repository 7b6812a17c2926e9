#pragma once
// `retrace generate-campus` as a library call: a campus world file around a route
// (campus_generator.hpp), checked, with a header that says how to make it again, and
// optionally a scenario that drives the route in it.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/worldgen/clutter_block.hpp"
#include "core/pose2.hpp"

namespace retrace::bench {

struct GenerateCampusOptions {
  std::filesystem::path route_file;  ///< x y per line, or an AutoNavi path
  std::filesystem::path out;         ///< the world file to write (YAML)
  std::uint64_t seed = 1;
  std::filesystem::path config_file;   ///< optional YAML with a CampusConfig
  std::vector<std::string> overrides;  ///< --set key=value on the CampusConfig
  int pedestrians = -1;                ///< overrides CampusConfig::pedestrians when >= 0
  /// Optional: a scenario to write that drives the route in the world (with the clutter block).
  std::filesystem::path scenario;
  ClutterOptions clutter;  ///< needs `scenario`
};

/// Reads the route and the generator config, generates the campus, checks that the route is
/// drivable in it, writes the world file atomically with a comment header that says how it
/// was generated, loads it back and checks it again. Returns a one-line summary (objects by
/// kind, route length). With options.scenario, also writes a scenario (route switch points
/// `auto`, the clutter block of options.clutter) that names the world and route by paths
/// relative to it. Throws core::IoError (missing or malformed route or config file,
/// a route of fewer than 2 points), core::ConfigError (unknown or invalid config key) or
/// core::WorldError; nothing is written then.
std::string GenerateCampusWorld(const GenerateCampusOptions& options);

/// The same for a route in hand, writing the world to `file` (e.g. inside a staging folder)
/// while its header names options.route_file and options.out, where the files will be.
std::string WriteCampusWorld(const std::vector<core::Vec2>& route,
                             const GenerateCampusOptions& options,
                             const std::filesystem::path& file);

}  // namespace retrace::bench
