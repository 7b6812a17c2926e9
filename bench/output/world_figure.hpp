#pragma once
// `retrace world` as a library call: load and check a world file (and a route in it), spawn its
// pedestrians, render it to a PNG.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace retrace::bench {

struct WorldCommandOptions {
  std::filesystem::path world_file;
  std::filesystem::path png;
  std::filesystem::path route_file;  ///< optional route to draw
  std::vector<std::string> overrides;
  double pixels_per_meter = 0.0;  ///< 0: a figure 1600 px wide
  std::uint64_t seed = 1;         ///< seed of the pedestrians' spawn points
};

/// Loads and validates a world file and renders it to a PNG.
/// Returns a one-line summary; throws core::Error on bad input.
std::string RenderWorldFile(const WorldCommandOptions& options);

}  // namespace retrace::bench
