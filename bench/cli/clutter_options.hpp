#pragma once
// --clutter-density and --standing-density of `retrace generate-campus --scenario` and
// `retrace generate-tour` (bench/worldgen/clutter_block.hpp writes the block they ask for).

#include "bench/worldgen/clutter_block.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

/// Adds --clutter-density and --standing-density to `cmd`, writing into `options`.
void AddClutterOptions(CLI::App* cmd, ClutterOptions* options);

}  // namespace retrace::bench
