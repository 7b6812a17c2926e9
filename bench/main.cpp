// The `retrace` command-line program. Every subcommand turns bad input into one clear line on
// stderr and exit code 2.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <iostream>

#include "bench/world_command.hpp"
#include "core/errors.hpp"

namespace {

constexpr int kExitBadInput = 2;

}  // namespace

int main(int argc, char** argv) {
  using namespace retrace;
  CLI::App app{"retrace: teaching-playback navigation without a consistent map, simulated"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "retrace 0.1.0");

  bench::WorldCommandOptions world;
  CLI::App* world_cmd = app.add_subcommand("world", "Load and check a world file, render it to a PNG");
  world_cmd->add_option("world", world.world_file, "World file (YAML)")->required();
  world_cmd->add_option("--png", world.png, "Output image")->required();
  world_cmd->add_option("--route", world.route_file, "Route file to draw (x y per line or AutoNavi path)");
  world_cmd->add_option("--set", world.overrides, "Override a key: a.b.c=value (repeatable)");
  world_cmd->add_option("--pixels-per-meter", world.pixels_per_meter, "Image scale")
      ->check(CLI::PositiveNumber);
  world_cmd->add_option("--seed", world.seed, "Seed for the pedestrians' spawn points");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "retrace: error: " << e.what() << " (see retrace --help)\n";
    return kExitBadInput;
  }

  try {
    if (*world_cmd) std::cout << bench::RunWorldCommand(world) << "\n";
  } catch (const core::Error& e) {
    std::cerr << "retrace: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "retrace: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
