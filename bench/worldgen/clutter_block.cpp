#include "bench/worldgen/clutter_block.hpp"

#include "bench/engine/clutter.hpp"
#include "core/config.hpp"
#include "core/errors.hpp"

namespace retrace::bench {

std::string ClutterBlock(const ClutterOptions& options) {
  if (!options.any()) return "";
  ClutterConfig config;
  config.density = options.density;
  config.standing_density = options.standing_density;
  try {
    config.Validate();
  } catch (const core::ConfigError& e) {
    const char* option = e.key_path() == "density" ? "--clutter-density" : "--standing-density";
    throw core::ConfigError(option, e.detail());
  }
  return "clutter: {density: " + core::FormatNumber(options.density) +
         ", standing_density: " + core::FormatNumber(options.standing_density) + "}\n";
}

std::string ClutterArguments(const ClutterOptions& options) {
  std::string out;
  if (options.density != 0.0) out += " --clutter-density " + core::FormatNumber(options.density);
  if (options.standing_density != 0.0) {
    out += " --standing-density " + core::FormatNumber(options.standing_density);
  }
  return out;
}

}  // namespace retrace::bench
