// Loading a world that imports a large ROS map: a 2000 x 2000 cell (100 m x 100 m at 5 cm)
// floor plan with rooms, doors and furniture, read from PGM and turned into merged two-sided
// edges. Target (issue 2): well under 2 s. The map is generated once per process into a
// temporary folder.
//
//   ./retrace_micro_bench --benchmark_filter=MapImport

#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>

#include "core/occupancy_grid.hpp"
#include "core/rng.hpp"
#include "io/ros_map.hpp"
#include "sim/physics_world.hpp"
#include "sim/ray_caster.hpp"
#include "sim/world_file.hpp"

namespace {

namespace fs = std::filesystem;
using retrace::core::CellIndex;

constexpr int kCells = 2000;
constexpr double kResolution = 0.05;

// Rooms of 5 m with 20 cm walls and 1 m doors, and random furniture blocks.
retrace::core::OccupancyGrid MakeFloorPlan() {
  retrace::core::OccupancyGrid grid(kCells, kCells, kResolution, {0.0, 0.0});
  retrace::core::Rng rng(7);
  const float occupied = static_cast<float>(retrace::core::Logit(0.95));
  const float free_l = static_cast<float>(retrace::core::Logit(0.05));
  std::fill(grid.log_odds().begin(), grid.log_odds().end(), free_l);
  const int pitch = 100;  // cells per room
  const int wall = 4;
  for (int y = 0; y < kCells; ++y) {
    for (int x = 0; x < kCells; ++x) {
      const bool wall_x = x % pitch < wall;
      const bool wall_y = y % pitch < wall;
      const bool door_x = (y % pitch) > 40 && (y % pitch) < 60;  // doors in vertical walls
      const bool door_y = (x % pitch) > 40 && (x % pitch) < 60;
      if ((wall_x && !door_x) || (wall_y && !door_y)) grid.SetLogOdds({x, y}, occupied);
    }
  }
  for (int i = 0; i < 3000; ++i) {
    const int x0 = static_cast<int>(rng.UniformIndex(kCells - 30));
    const int y0 = static_cast<int>(rng.UniformIndex(kCells - 30));
    const int w = 4 + static_cast<int>(rng.UniformIndex(20));
    const int h = 4 + static_cast<int>(rng.UniformIndex(20));
    for (int y = y0; y < y0 + h; ++y) {
      for (int x = x0; x < x0 + w; ++x) grid.SetLogOdds({x, y}, occupied);
    }
  }
  return grid;
}

const fs::path& MapWorldFile() {
  static const fs::path world = [] {
    const fs::path dir = fs::temp_directory_path() / "retrace_map_import_bench";
    fs::create_directories(dir);
    retrace::io::WriteRosMap(dir / "floor.yaml", MakeFloorPlan());
    std::ofstream(dir / "world.yaml") << "name: floor\nmaps: [{file: floor.yaml}]\n";
    return dir / "world.yaml";
  }();
  return world;
}

void BM_MapImport2000x2000(benchmark::State& state) {
  const fs::path& file = MapWorldFile();
  std::size_t edges = 0;
  for (auto _ : state) {
    const retrace::sim::World world = retrace::sim::LoadWorld(file);
    edges = world.geometry.segments().size();
    benchmark::DoNotOptimize(edges);
  }
  state.counters["edges"] = static_cast<double>(edges);
  state.counters["cells"] = static_cast<double>(kCells) * kCells;
}
BENCHMARK(BM_MapImport2000x2000)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same plus everything a simulation builds from the geometry: the Box2D world (one
// two-sided edge fixture per merged edge) and the LiDAR's ray-casting grid.
void BM_MapImport2000x2000WithPhysicsAndRayCaster(benchmark::State& state) {
  const fs::path& file = MapWorldFile();
  for (auto _ : state) {
    const retrace::sim::World world = retrace::sim::LoadWorld(file);
    const retrace::sim::PhysicsWorld physics(world.geometry);
    const retrace::sim::RayCaster caster(world.geometry);
    benchmark::DoNotOptimize(caster.entry_count());
  }
}
BENCHMARK(BM_MapImport2000x2000WithPhysicsAndRayCaster)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
