#include "bench/cli/world_command.hpp"

#include <CLI/CLI.hpp>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/shared_options.hpp"

namespace retrace::bench {

void AddWorldOptions(CLI::App* cmd, WorldCommandOptions* options) {
  cmd->add_option("world", options->world_file, "World file (YAML)")->required();
  cmd->add_option("--png", options->png, "Output image")->required();
  cmd->add_option("--route", options->route_file,
                  "Route file to draw (x y per line or AutoNavi path)");
  AddSetOption(cmd, &options->overrides, "a key: a.b.c=value");
  cmd->add_option("--pixels-per-meter", options->pixels_per_meter,
                  "Image scale (default: 1600 px wide)")
      ->check(kPositive);
  AddSeedOption(cmd, &options->seed, "for the pedestrians' spawn points");
}

}  // namespace retrace::bench
