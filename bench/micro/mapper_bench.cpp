// The teaching drive's mapper (nav/mapper.hpp) per keyframe: integrating full 1081-beam scans
// (270°, 30 m, 2 cm range noise) taken 0.5 m apart along a 100 m drive through the procedurally
// generated campus of the likelihood benchmark, into one map that grows as the drive goes — what
// each map mode's recorder does at every keyframe.
//
//   ./retrace_micro_bench --benchmark_filter=Mapper --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "bench/micro/campus_map.hpp"
#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "nav/grid_ray_caster.hpp"
#include "nav/likelihood_field.hpp"
#include "nav/mapper.hpp"

namespace {

using retrace::core::Pose2;

constexpr int kKeyframes = 200;

const retrace::bench_micro::CampusDrive& GetMapperFixture() {
  static const retrace::bench_micro::CampusDrive f =
      retrace::bench_micro::DriveThroughCampus(kKeyframes, 0.02, 7);
  return f;
}

// A fresh map, then every keyframe of the drive: items are keyframes.
void BM_MapperKeyframe(benchmark::State& state) {
  const retrace::bench_micro::CampusDrive& f = GetMapperFixture();
  for (auto _ : state) {
    retrace::nav::Mapper mapper({}, {});
    for (std::size_t k = 0; k < f.scans.size(); ++k) {
      mapper.SetPose(f.poses[k]);
      mapper.Integrate(f.scans[k], f.poses[k]);
    }
    benchmark::DoNotOptimize(mapper.grid().log_odds().data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * kKeyframes);
}
BENCHMARK(BM_MapperKeyframe)->Unit(benchmark::kMillisecond);

}  // namespace
