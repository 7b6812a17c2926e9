#include "bench/world_command.hpp"

#include <sstream>

#include "core/errors.hpp"
#include "io/config_yaml.hpp"
#include "io/route_file.hpp"
#include "core/rng.hpp"
#include "sim/pedestrians.hpp"
#include "sim/physics_world.hpp"
#include "sim/robot.hpp"
#include "sim/route_check.hpp"
#include "sim/world_file.hpp"
#include "viz/world_sketch.hpp"

namespace retrace::bench {

std::string RunWorldCommand(const WorldCommandOptions& options) {
  std::vector<io::ConfigOverride> overrides;
  for (const auto& s : options.overrides) overrides.push_back(io::ParseOverride(s));
  const sim::World world = sim::LoadWorld(options.world_file, overrides);

  viz::SketchScene scene;
  const auto& g = world.geometry;
  scene.solids = g.polygons();
  // Edges that are not polygon outlines (imported maps) are drawn as lines.
  std::size_t polygon_edges = 0;
  for (const auto& ring : g.polygons()) polygon_edges += ring.size();
  for (std::size_t i = polygon_edges; i < g.segments().size(); ++i) {
    scene.edges.emplace_back(g.segments()[i].a, g.segments()[i].b);
  }
  for (const auto& c : g.circles()) scene.discs.emplace_back(c.center, c.radius);
  if (!options.route_file.empty()) {
    scene.route = io::ReadRouteFile(options.route_file);
    try {
      sim::CheckRouteIsDrivable(g, scene.route, sim::RobotConfig{}.radius);
    } catch (const core::WorldError& e) {
      throw core::WorldError(options.route_file.string() + ": " + e.what());
    }
  }

  // Spawning the pedestrians checks that their regions and loops work in this geometry.
  std::vector<sim::Circle> keep_clear;
  if (!scene.route.empty()) keep_clear.push_back({scene.route.front(), sim::RobotConfig{}.radius});
  sim::PhysicsWorld physics(g);
  const sim::Pedestrians crowd(world.config.pedestrians, sim::CrowdConfig{}, g,
                               core::Rng(options.seed).Split("pedestrians"), keep_clear, physics);
  for (const auto& c : physics.PedestrianCircles()) scene.pedestrians.emplace_back(c.center, c.radius);

  viz::SketchOptions sketch;
  sketch.pixels_per_meter = options.pixels_per_meter;
  viz::RenderSketchPng(scene, options.png, sketch);

  const sim::Aabb box = g.Bounds();
  std::ostringstream out;
  out << world.source.string() << ": " << g.segments().size() << " edges, " << g.circles().size()
      << " circles, " << crowd.size() << " pedestrians, extent "
      << (box.max - box.min).x() << " x " << (box.max - box.min).y() << " m -> "
      << options.png.string();
  return out.str();
}

}  // namespace retrace::bench
