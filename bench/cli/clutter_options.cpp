#include "bench/cli/clutter_options.hpp"

#include <CLI/CLI.hpp>
#include <cmath>

#include "bench/cli/cli_checks.hpp"
#include "bench/engine/clutter.hpp"
#include "core/errors.hpp"

namespace retrace::bench {

void AddClutterOptions(CLI::App* cmd, ClutterOptions* options) {
  cmd->add_option("--clutter-density", options->density,
                  "Unmapped static objects (chairs, bins, bikes, boxes) per m² of the band beside "
                  "the route during playback: the scenario's clutter.density (default 0: none; " +
                      core::FormatNumber(
                          std::round(1000.0 * CalibratedClutterDensity(ClutterConfig{})) / 1000.0) +
                      " is the density calibrated on a real log)")
      ->check(kNonNegative);
  cmd->add_option("--standing-density", options->standing_density,
                  "People standing still per m² of the band during playback: the scenario's "
                  "clutter.standing_density (default 0: none)")
      ->check(kNonNegative);
}

}  // namespace retrace::bench
