#include "bench/output/world_figure.hpp"

#include <algorithm>
#include <sstream>

#include "bench/output/world_shapes.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "io/config_yaml.hpp"
#include "io/route_file.hpp"
#include "sim/pedestrians.hpp"
#include "sim/physics_world.hpp"
#include "sim/robot.hpp"
#include "sim/route_check.hpp"
#include "sim/walk_planner.hpp"
#include "sim/world_file.hpp"
#include "viz/figures.hpp"

namespace retrace::bench {

std::string RenderWorldFile(const WorldCommandOptions& options) {
  std::vector<io::ConfigOverride> overrides;
  for (const auto& s : options.overrides) overrides.push_back(io::ParseOverride(s));
  const sim::World world = sim::LoadWorld(options.world_file, overrides);

  const auto& g = world.geometry;
  viz::WorldFigureData figure;
  figure.name = world.source.stem().string();
  figure.world = WorldShapesOf(g);
  figure.robot_radius = sim::RobotConfig{}.radius;  // a world has no robot: the default one
  if (!options.route_file.empty()) {
    figure.route = io::ReadRouteFile(options.route_file);
    try {
      sim::CheckRouteIsDrivable(g, figure.route, sim::RobotConfig{}.radius);
    } catch (const core::WorldError& e) {
      throw core::WorldError(options.route_file.string() + ": " + e.what());
    }
  }

  // Spawning the pedestrians checks that their regions and loops work in this geometry.
  std::vector<sim::Circle> keep_clear;
  if (!figure.route.empty())
    keep_clear.push_back({figure.route.front(), sim::RobotConfig{}.radius});
  sim::PhysicsWorld physics(g);
  const sim::Pedestrians crowd(world.config.pedestrians, sim::CrowdConfig{}, g,
                               core::Rng(options.seed).Split("pedestrians"), keep_clear, physics);
  for (const auto& c : physics.PedestrianCircles())
    figure.pedestrians.push_back({c.center, c.radius});

  // The figure's width follows the requested scale, within what the renderer allows.
  const viz::Box2 extent = figure.world.Bounds();
  viz::FigureOptions figure_options;
  if (options.pixels_per_meter > 0.0 && !extent.IsEmpty()) {
    const double width = extent.Size().x() * options.pixels_per_meter + 160.0;
    figure_options.width = static_cast<int>(std::clamp(width, 400.0, 8000.0));
  }
  viz::RenderWorldFigure(figure, options.png, figure_options);

  const sim::Aabb box = g.Bounds();
  std::ostringstream out;
  out << world.source.string() << ": " << g.segments().size() << " edges, " << g.circles().size()
      << " circles, " << crowd.size() << " pedestrians, extent " << (box.max - box.min).x() << " x "
      << (box.max - box.min).y() << " m -> " << options.png.string();
  // A large pedestrian area is planned on coarser cells than configured: say so.
  if (const sim::WalkPlanner* planner = crowd.planner();
      planner != nullptr && planner->cell_size() > sim::CrowdConfig{}.planner.cell_size) {
    out << "\nnote: the pedestrians' walk planner uses " << planner->cell_size() << " m cells over "
        << planner->width() << " x " << planner->height() << " cells (the area is too large for "
        << sim::CrowdConfig{}.planner.cell_size << " m)";
  }
  return out.str();
}

}  // namespace retrace::bench
