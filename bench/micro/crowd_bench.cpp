// The crowd's cost per pedestrian and step: Pedestrians::Update (waypoints, the interaction model,
// walls, the robot) for the social force and the time-to-collision model, in an empty square hall
// at 1 person/m² with a robot standing in it; Box2D's step is outside the timing. The `ttc` /
// `social_force` ratio of per_pedestrian (the time per pedestrian and step) is what docs/BENCHMARKS.md reports.
//
//   ./retrace_micro_bench --benchmark_filter=Crowd

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "core/rng.hpp"
#include "sim/pedestrians.hpp"
#include "sim/physics_world.hpp"
#include "sim/robot.hpp"

namespace {

using namespace retrace;

// A hall of `people` m² with a 0.2 m wall round it, the robot in the middle and `people`
// pedestrians wandering in it, warmed up for 5 s.
struct Hall {
  sim::StaticGeometry geometry;
  std::unique_ptr<sim::PhysicsWorld> world;
  std::unique_ptr<sim::Robot> robot;
  std::unique_ptr<sim::Pedestrians> crowd;

  Hall(int people, sim::CrowdModel model) {
    const double half = 0.5 * std::sqrt(static_cast<double>(people));
    const double t = 0.2;
    geometry.AddPolygon(
        {{-half - t, -half - t}, {half + t, -half - t}, {half + t, -half}, {-half - t, -half}});
    geometry.AddPolygon(
        {{-half - t, half}, {half + t, half}, {half + t, half + t}, {-half - t, half + t}});
    geometry.AddPolygon({{-half - t, -half}, {-half, -half}, {-half, half}, {-half - t, half}});
    geometry.AddPolygon({{half, -half}, {half + t, -half}, {half + t, half}, {half, half}});
    world = std::make_unique<sim::PhysicsWorld>(geometry);
    robot = std::make_unique<sim::Robot>(sim::RobotConfig{}, geometry, core::Pose2(0.0, 0.0, 0.0),
                                         *world);
    sim::PedestrianGroupConfig group;
    group.count = people;
    group.region_min = {-half + 0.3, -half + 0.3};
    group.region_max = {half - 0.3, half - 0.3};
    group.radius = 0.2;
    sim::CrowdConfig config;
    config.model = model;
    config.spawn_gap = 0.05;
    crowd = std::make_unique<sim::Pedestrians>(std::vector<sim::PedestrianGroupConfig>{group},
                                               config, geometry, core::Rng(1),
                                               std::vector<sim::Circle>{{{0.0, 0.0}, 0.3}}, *world);
    for (int i = 0; i < 500; ++i) Step();
  }
  void Step() {
    crowd->Update(*world);
    world->Step();
  }
};

void BM_CrowdUpdate(benchmark::State& state) {
  const int people = static_cast<int>(state.range(0));
  const auto model = static_cast<sim::CrowdModel>(state.range(1));
  Hall hall(people, model);
  for (auto _ : state) {
    hall.crowd->Update(*hall.world);
    state.PauseTiming();
    hall.world->Step();
    state.ResumeTiming();
  }
  state.counters["per_pedestrian"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * people,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.SetLabel(std::string(core::EnumName(model)));
}
BENCHMARK(BM_CrowdUpdate)
    ->ArgsProduct({{30, 100, 300},
                   {static_cast<int>(sim::CrowdModel::kSocialForce),
                    static_cast<int>(sim::CrowdModel::kTtc)}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
