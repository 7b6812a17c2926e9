#include "bench/worldgen/tour_folder.hpp"

#include <cmath>
#include <sstream>

#include "bench/engine/switch_points.hpp"
#include "bench/output/staged_folder.hpp"
#include "bench/worldgen/campus_world.hpp"
#include "bench/worldgen/tour_generator.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/config_yaml.hpp"

namespace retrace::bench {
namespace {

TourConfig LoadTourConfig(const GenerateTourOptions& options) {
  std::vector<io::ConfigOverride> overrides;
  for (const auto& s : options.overrides) overrides.push_back(io::ParseOverride(s));
  YAML::Node root(YAML::NodeType::Map);
  io::ApplyOverrides(root, overrides);
  return io::ReadConfig<TourConfig>(root, "generate-tour", overrides);
}

// The command that makes the folder again.
std::string CommandLine(const GenerateTourOptions& options) {
  std::string cmd = "retrace generate-tour --seed " + std::to_string(options.seed);
  for (const std::string& s : options.overrides) cmd += " --set " + s;
  if (options.pedestrians != GenerateTourOptions{}.pedestrians)
    cmd += " --pedestrians " + std::to_string(options.pedestrians);
  cmd += ClutterArguments(options.clutter);
  return cmd + " --out " + options.out.string();
}

std::string RouteText(const std::vector<core::Vec2>& route, const TourConfig& config,
                      const std::string& command) {
  std::ostringstream out;
  out << "# A random looped tour (`" << command << "`), " << std::lround(RouteLength(route))
      << " m on a " << config.columns << " x " << config.rows
      << " street grid (x y, metres, frame W).\n";
  for (const core::Vec2& p : route) {
    out << core::FormatNumber(std::round(p.x() * 1000.0) / 1000.0) << " "
        << core::FormatNumber(std::round(p.y() * 1000.0) / 1000.0) << "\n";
  }
  return out.str();
}

std::string ScenarioText(const std::string& name, std::uint64_t seed, const std::string& command,
                         const std::string& clutter) {
  std::ostringstream out;
  out << "# A random looped tour written by `" << command << "`: the route in route.txt,\n"
      << "# a campus round it in world.yaml. Switch points come from the route's geometry; try\n"
      << "# `--set route.switch_points=online` to let the teach recorder choose them.\n"
      << "name: " << name << "\n"
      << "world: world.yaml\n"
      << "route:\n"
      << "  file: route.txt\n"
      << "  switch_points: auto\n"
      << "  revisit_radius: 5.0\n"
      << "seed: " << seed << "\n"
      << "modes: [partial, scan_matched, consistent]\n"
      << "teach:\n"
      << "  teacher: {speed: 1.0}\n"
      << "playback:\n"
      << "  repeats: 3\n"
      << "sim:\n"
      << "  crowd: {planner: {cell_size: 0.25}}\n"
      << "nav:\n"
      << "  follower: {max_speed: 1.0}\n"
      << clutter;
  return out.str();
}

}  // namespace

std::string GenerateTourFolder(const GenerateTourOptions& options) {
  if (options.out.empty()) throw core::ConfigError("--out", "needs the folder to write");
  const TourConfig config = LoadTourConfig(options);
  const std::string clutter = ClutterBlock(options.clutter);  // checked before anything is built
  const std::vector<core::Vec2> route = GenerateTour(config, options.seed);

  StagedFolder folder(options.out);
  const std::string command = CommandLine(options);
  io::WriteFileAtomic(folder.path() / "route.txt", RouteText(route, config, command));
  GenerateCampusOptions campus;
  campus.route_file = options.out / "route.txt";
  campus.out = options.out / "world.yaml";
  campus.seed = options.seed;
  campus.pedestrians = options.pedestrians;
  const std::string world = WriteCampusWorld(route, campus, folder.path() / "world.yaml");
  const std::string name = "tour-" + std::to_string(options.seed);
  io::WriteFileAtomic(folder.path() / "scenario.yaml",
                      ScenarioText(name, options.seed, command, clutter));
  folder.Commit();
  return options.out.string() + ": a " + std::to_string(std::lround(RouteLength(route))) +
         " m tour of " + std::to_string(route.size()) + " waypoints; " + world +
         "\nrun it: retrace run " + (options.out / "scenario.yaml").string();
}

}  // namespace retrace::bench
