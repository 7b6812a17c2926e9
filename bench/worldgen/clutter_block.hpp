#pragma once
// The clutter densities a generated scenario asks for (`retrace generate-campus --scenario`,
// `retrace generate-tour`): the scenario's `clutter` block (bench/engine/clutter.hpp) and the
// command-line words that ask for it again.

#include <string>

namespace retrace::bench {

struct ClutterOptions {
  double density = 0.0;           ///< --clutter-density: objects per m² of the band
  double standing_density = 0.0;  ///< --standing-density: people standing still per m²
  bool any() const { return density != 0.0 || standing_density != 0.0; }
};

/// The scenario's clutter block for these densities, one line ending in a newline; "" when
/// both are 0 (the scenario then has no clutter, as before these options). Throws
/// core::ConfigError naming the option for a density the scenario would refuse.
std::string ClutterBlock(const ClutterOptions& options);

/// The options as they appear on a command line (" --clutter-density 0.03 ..."), "" at 0.
std::string ClutterArguments(const ClutterOptions& options);

}  // namespace retrace::bench
