#pragma once
// `retrace generate-tour`: the options of bench/worldgen/tour_folder.hpp's GenerateTourFolder,
// which the command table runs.

#include "bench/cli/clutter_options.hpp"
#include "bench/worldgen/tour_folder.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

/// Adds --out, --seed, --set, --pedestrians, --clutter-density and --standing-density to `cmd`,
/// writing into `options`.
void AddGenerateTourOptions(CLI::App* cmd, GenerateTourOptions* options);

}  // namespace retrace::bench
