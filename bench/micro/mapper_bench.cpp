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

struct MapperFixture {
  std::vector<Pose2> poses;
  std::vector<retrace::core::LaserScan> scans;

  MapperFixture() {
    const retrace::core::OccupancyGrid map = retrace::bench_micro::CampusMap();
    const retrace::nav::LikelihoodField field(map, {}, 30.0);
    const retrace::nav::GridRayCaster caster(field);
    retrace::core::Rng rng(7);
    Pose2 X = retrace::bench_micro::FreeCampusPose(map, field, rng);
    while (static_cast<int>(poses.size()) < kKeyframes) {
      const double ahead = caster.Cast(X.x, X.y, std::cos(X.theta), std::sin(X.theta), 30.0);
      if (ahead < 2.0) {
        X = Pose2(X.x, X.y, X.theta + 0.6);
        continue;
      }
      poses.push_back(X);
      scans.push_back(retrace::bench_micro::CampusScan(caster, X, rng));
      X = X * Pose2(0.5, 0.0, 0.02);
    }
  }
};

const MapperFixture& GetMapperFixture() {
  static const MapperFixture f;
  return f;
}

// A fresh map, then every keyframe of the drive: items are keyframes.
void BM_MapperKeyframe(benchmark::State& state) {
  const MapperFixture& f = GetMapperFixture();
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
