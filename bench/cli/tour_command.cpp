#include "bench/cli/tour_command.hpp"

#include <CLI/CLI.hpp>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/shared_options.hpp"

namespace retrace::bench {

void AddGenerateTourOptions(CLI::App* cmd, GenerateTourOptions* options) {
  AddOutOption(cmd, &options->out, "Folder to write: route.txt, world.yaml, scenario.yaml")
      ->required();
  AddSeedOption(cmd, &options->seed, "of the tour and its world");
  AddSetOption(cmd, &options->overrides,
               "a tour setting: key=value (length, columns, rows, block_size, max_loop_blocks, "
               "max_transfer)");
  cmd->add_option("--pedestrians", options->pedestrians, "Pedestrians in the world (default 20)")
      ->check(kNonNegative);
  AddClutterOptions(cmd, &options->clutter);
}

}  // namespace retrace::bench
