#pragma once
// `retrace generate-campus`: the options of bench/worldgen/campus_world.hpp's
// GenerateCampusWorld, which the command table runs.

#include "bench/cli/clutter_options.hpp"
#include "bench/worldgen/campus_world.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

/// Adds the positional route file and --out, --seed, --config, --set, --pedestrians, --scenario,
/// --clutter-density and --standing-density to `cmd`, writing into `options` (which must
/// outlive the parse).
void AddGenerateCampusOptions(CLI::App* cmd, GenerateCampusOptions* options);

}  // namespace retrace::bench
