#pragma once
// `retrace generate-tour` as a library call: a seeded random looped tour (tour_generator.hpp), a
// campus world round it and a scenario that drives it — a folder users run with `retrace run`
// to stress map switching and their settings on routes nobody picked by hand.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/worldgen/clutter_block.hpp"

namespace retrace::bench {

struct GenerateTourOptions {
  std::filesystem::path out;           ///< the folder to write
  std::uint64_t seed = 1;              ///< of the tour, the world and the scenario
  std::vector<std::string> overrides;  ///< --set key=value on the TourConfig
  int pedestrians = 20;
  ClutterOptions clutter;  ///< the scenario's clutter block (none at 0)
};

/// Writes, atomically, the folder `out` with route.txt (the tour), world.yaml (a campus round it)
/// and scenario.yaml (route.switch_points: auto, modes partial, scan_matched and consistent,
/// the clutter block when a density is given).
/// Returns a one-line summary. Throws core::ConfigError for an invalid tour setting.
std::string GenerateTourFolder(const GenerateTourOptions& options);

}  // namespace retrace::bench
