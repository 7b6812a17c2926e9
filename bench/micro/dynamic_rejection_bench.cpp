// The dynamic scan point test (eq. 7-9) for one localizer update: 500 particles x 108 beams,
// each needing the expected range of its ray on the map. retrace's TestDynamicBeams with
// sphere tracing on the distance field against the same test with per-cell DDA ray marching
// (GridRayCaster::CastDda), in the same run, on the procedurally generated 300 m x 300 m
// campus at 0.1 m of likelihood_bench.cpp with a 30 m LiDAR and pedestrians shortening 20 % of
// the beams. Both must give the same mask: `mismatches` counts beams whose classification
// differs (and `ratio_mismatches` beams whose ratio differs in any bit); both must be 0.
//
//   ./retrace_micro_bench --benchmark_filter=Dynamic --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/angle.hpp"
#include "core/laser_scan.hpp"
#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "nav/beam_model.hpp"
#include "nav/grid_ray_caster.hpp"
#include "nav/likelihood_field.hpp"

namespace retrace_bench {
// Defined in likelihood_bench.cpp.
retrace::core::OccupancyGrid CampusMap();
}  // namespace retrace_bench

namespace {

using retrace::core::Pose2;
using retrace::core::Rng;
using retrace::nav::BeamModel;
using retrace::nav::DynamicBeamResult;
using retrace::nav::RayCastMethod;

constexpr int kParticles = 500;

struct Fixture {
  retrace::core::OccupancyGrid map = retrace_bench::CampusMap();
  retrace::nav::LikelihoodField field{map, {}, 30.0};
  retrace::nav::GridRayCaster caster{field};
  BeamModel model{{}, 30.0};
  retrace::core::LaserScan scan;
  std::vector<Pose2> X_ML;
  std::vector<int> beams;
  int pedestrian_beams = 0;

  Fixture() {
    Rng rng(11);
    Pose2 truth;
    while (true) {
      truth = Pose2(rng.Uniform(-50, 50), rng.Uniform(-50, 50), rng.Uniform(-3, 3));
      if (field.Distance(map.WorldToCell(truth.translation())) > 1.5f) break;
    }
    scan.angle_min = -retrace::core::DegToRad(135.0);
    scan.angle_increment = retrace::core::DegToRad(0.25);
    scan.range_min = 0.05;
    scan.range_max = 30.0;
    for (std::size_t i = 0; i < 1081; ++i) {
      const double a = truth.theta + scan.Angle(i);
      double r = caster.Cast(truth.x, truth.y, std::cos(a), std::sin(a), 30.0);
      if (rng.Bernoulli(0.2)) {  // a pedestrian in front of whatever the beam would meet
        r = rng.Uniform(0.5, std::min(r, 10.0));
        if (i % 10 == 0) ++pedestrian_beams;
      }
      r += 0.02 * rng.Normal();
      scan.ranges.push_back(r > 30.0 ? std::numeric_limits<float>::infinity() : static_cast<float>(r));
    }
    for (std::size_t i = 0; i < scan.size(); i += 10) {
      if (scan.Valid(i)) beams.push_back(static_cast<int>(i));
    }
    for (int j = 0; j < kParticles; ++j) {
      X_ML.emplace_back(truth.x + 0.1 * rng.Normal(), truth.y + 0.1 * rng.Normal(),
                        truth.theta + 0.02 * rng.Normal());
    }
  }
};

const Fixture& GetFixture() {
  static const Fixture f;
  return f;
}

void Run(benchmark::State& state, RayCastMethod method) {
  const Fixture& f = GetFixture();
  DynamicBeamResult result, sphere, dda;
  // The check, outside the timed loop: both methods give the same ratios and mask.
  retrace::nav::TestDynamicBeams(f.model, f.caster, f.X_ML, {}, f.scan, f.beams, 0.9,
                                 RayCastMethod::kSphereTracing, &sphere);
  retrace::nav::TestDynamicBeams(f.model, f.caster, f.X_ML, {}, f.scan, f.beams, 0.9,
                                 RayCastMethod::kDda, &dda);
  int mismatches = 0, ratio_mismatches = 0, dynamic = 0;
  for (std::size_t b = 0; b < f.beams.size(); ++b) {
    mismatches += sphere.dynamic[b] != dda.dynamic[b] ? 1 : 0;
    ratio_mismatches +=
        std::bit_cast<std::uint64_t>(sphere.ratio[b]) != std::bit_cast<std::uint64_t>(dda.ratio[b]) ? 1 : 0;
    dynamic += sphere.dynamic[b];
  }
  for (auto _ : state) {
    retrace::nav::TestDynamicBeams(f.model, f.caster, f.X_ML, {}, f.scan, f.beams, 0.9, method,
                                   &result);
    benchmark::DoNotOptimize(result.dynamic.data());
  }
  const double rays = static_cast<double>(kParticles) * static_cast<double>(f.beams.size());
  state.counters["ns_per_particle_beam"] = benchmark::Counter(
      rays, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["beams"] = static_cast<double>(f.beams.size());
  state.counters["dynamic"] = dynamic;
  state.counters["pedestrian_beams"] = f.pedestrian_beams;
  state.counters["mismatches"] = mismatches;
  state.counters["ratio_mismatches"] = ratio_mismatches;
}

void BM_DynamicRejectionSphereTracing(benchmark::State& state) {
  Run(state, RayCastMethod::kSphereTracing);
}
BENCHMARK(BM_DynamicRejectionSphereTracing)->Unit(benchmark::kMillisecond);

void BM_DynamicRejectionDdaReference(benchmark::State& state) { Run(state, RayCastMethod::kDda); }
BENCHMARK(BM_DynamicRejectionDdaReference)->Unit(benchmark::kMillisecond);

}  // namespace
