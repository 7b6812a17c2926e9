#pragma once
// `retrace world`: the options of bench/output/world_figure.hpp's RenderWorldFile, which the
// command table runs.

#include "bench/output/world_figure.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

void AddWorldOptions(CLI::App* cmd, WorldCommandOptions* options);

}  // namespace retrace::bench
