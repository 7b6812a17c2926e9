// Whole-simulation throughput: the office world with its pedestrians, the teacher driving the
// double corridor loop, 1081-beam LiDAR at 20 Hz and odometry at 50 Hz, physics at 100 Hz.
// `real_time_factor` is simulated seconds per second of CPU on one core.
//
//   ./retrace_micro_bench --benchmark_filter=Simulator

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "core/rng.hpp"
#include "io/route_file.hpp"
#include "sim/simulator.hpp"
#include "sim/teacher.hpp"

namespace {

using namespace retrace;

struct Drive {
  sim::World world = sim::LoadWorld(std::string(RETRACE_SOURCE_DIR) + "/worlds/office.yaml");
  std::vector<core::Vec2> route =
      io::ReadRouteFile(std::string(RETRACE_SOURCE_DIR) + "/worlds/routes/office_loop.txt");
  std::unique_ptr<sim::Simulator> sim;
  std::unique_ptr<sim::Teacher> teacher;
  core::Twist command;
  int step = 0;

  void Restart() {
    const core::Rng rng(1);
    const core::Vec2 d = route[1] - route[0];
    sim = std::make_unique<sim::Simulator>(
        world, sim::SimConfig{}, core::Pose2(route[0].x(), route[0].y(), std::atan2(d.y(), d.x())), rng);
    teacher = std::make_unique<sim::Teacher>(route, sim::TeacherConfig{}, rng.Split("teacher"));
    step = 0;
  }
  // One simulated second: 100 physics steps, teacher commands at 20 Hz.
  void SimulateOneSecond() {
    for (int i = 0; i < 100; ++i, ++step) {
      if (step % 5 == 0) command = teacher->Command(sim->RobotPose(), 0.05);
      benchmark::DoNotOptimize(sim->Step(command));
    }
  }
};

void BM_SimulatorOfficeTeachDrive(benchmark::State& state) {
  Drive drive;
  drive.Restart();
  for (auto _ : state) {
    if (drive.teacher->Done()) {
      state.PauseTiming();
      drive.Restart();
      state.ResumeTiming();
    }
    drive.SimulateOneSecond();
  }
  state.counters["real_time_factor"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulatorOfficeTeachDrive)->Unit(benchmark::kMillisecond);

}  // namespace
