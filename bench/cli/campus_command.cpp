#include "bench/cli/campus_command.hpp"

#include <CLI/CLI.hpp>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/shared_options.hpp"

namespace retrace::bench {

void AddGenerateCampusOptions(CLI::App* cmd, GenerateCampusOptions* options) {
  cmd->add_option("route", options->route_file,
                  "Route file: one waypoint `x y` per line (W, m), or an AutoNavi path")
      ->required();
  AddOutOption(cmd, &options->out, "World file to write (YAML)")->required();
  AddSeedOption(cmd, &options->seed,
                "of the placement: the same route, settings and seed give the same world");
  AddConfigOption(
      cmd, &options->config_file,
      "YAML file with generator settings (CampusConfig in bench/worldgen/campus_generator.hpp)");
  AddSetOption(cmd, &options->overrides, "a generator setting: key=value, value in YAML")
      ->allow_extra_args(false);  // one value per --set, so that a positional may follow
  cmd->add_option(
         "--pedestrians", options->pedestrians,
         "Number of pedestrians, split into wander and loop groups (overrides the settings)")
      ->check(kNonNegative);
  cmd->add_option("--scenario", options->scenario,
                  "Also write a scenario (YAML) that drives the route in the world, with the "
                  "clutter block of --clutter-density and --standing-density");
  AddClutterOptions(cmd, &options->clutter);
}

}  // namespace retrace::bench
