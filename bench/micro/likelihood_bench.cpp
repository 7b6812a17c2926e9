// Likelihood-field weighting: retrace's table lookup (LikelihoodField::SumLogLikelihood, one
// rotation per particle and one float load per beam) against a straightforward weighting that
// evaluates eq. (5-6) per beam with trig, exp and log, in the same run. A procedurally generated
// 300 m x 300 m campus at 0.1 m (3000 x 3000 cells: buildings, walls, trees), a 30 m LiDAR,
// 500 particles x 108 beams.
//
//   ./retrace_micro_bench --benchmark_filter=Likelihood --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// ns_per_particle_beam is the time of one beam evaluation for one particle (shown in s with an
// SI prefix, e.g. 2.2n = 2.2 ns).

#include <benchmark/benchmark.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "bench/micro/campus_map.hpp"
#include "core/angle.hpp"
#include "core/laser_scan.hpp"
#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "nav/grid_ray_caster.hpp"
#include "nav/likelihood_field.hpp"

namespace {

using retrace::core::Pose2;
using retrace::core::Rng;
using retrace::core::Vec2;

constexpr int kCells = retrace::bench_micro::kCampusCells;
constexpr double kRes = retrace::bench_micro::kCampusResolution;
constexpr int kParticles = 500;
constexpr int kBeamStep = 10;

struct Fixture {
  retrace::core::OccupancyGrid map = retrace::bench_micro::CampusMap();
  retrace::nav::LikelihoodField field{map, {}, 30.0};
  std::vector<Pose2> X_ML;     // particle LiDAR poses
  std::vector<double> xs, ys;  // used beam end points in L
  std::vector<double> ranges, angles;

  Fixture() {
    retrace::nav::GridRayCaster caster(field);
    Rng rng(7);
    const Pose2 truth = retrace::bench_micro::FreeCampusPose(map, field, rng);
    const double angle_min = -retrace::core::DegToRad(135.0), inc = retrace::core::DegToRad(0.25);
    for (int i = 0; i < 1081; i += kBeamStep) {
      const double a = angle_min + i * inc;
      double r = caster.Cast(truth.x, truth.y, std::cos(truth.theta + a), std::sin(truth.theta + a), 30.0);
      if (std::isinf(r)) r = rng.Uniform(5.0, 30.0);  // keep 108 beams: a return from unmapped clutter
      r += 0.02 * rng.Normal();
      ranges.push_back(r);
      angles.push_back(a);
      xs.push_back(r * std::cos(a));
      ys.push_back(r * std::sin(a));
    }
    for (int j = 0; j < kParticles; ++j) {
      X_ML.emplace_back(truth.x + 0.2 * rng.Normal(), truth.y + 0.2 * rng.Normal(),
                        truth.theta + 0.05 * rng.Normal());
    }
  }
};

const Fixture& GetFixture() {
  static const Fixture f;
  return f;
}

void SetCounters(benchmark::State& state, std::size_t beams) {
  const double evals = static_cast<double>(kParticles) * static_cast<double>(beams);
  state.counters["ns_per_particle_beam"] = benchmark::Counter(
      evals, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["beams"] = static_cast<double>(beams);
}

void BM_LikelihoodTableLookup(benchmark::State& state) {
  const Fixture& f = GetFixture();
  std::vector<double> log_w(kParticles);
  for (auto _ : state) {
    for (int j = 0; j < kParticles; ++j) {
      log_w[static_cast<std::size_t>(j)] =
          f.field.SumLogLikelihood(f.X_ML[static_cast<std::size_t>(j)], f.xs.data(), f.ys.data(), f.xs.size());
    }
    benchmark::DoNotOptimize(log_w.data());
    benchmark::ClobberMemory();
  }
  SetCounters(state, f.xs.size());
}
BENCHMARK(BM_LikelihoodTableLookup)->Unit(benchmark::kMicrosecond);

// Reference: per beam a cos/sin of the world angle, the distance from the distance field, and
// eq. (5-6) evaluated with exp and log.
void BM_LikelihoodNaiveReference(benchmark::State& state) {
  const Fixture& f = GetFixture();
  const retrace::nav::LikelihoodFieldConfig c;
  const double norm = 1.0 / (std::sqrt(2.0 * std::numbers::pi) * c.sigma_hit);
  const Vec2 origin = f.field.origin();
  std::vector<double> log_w(kParticles);
  for (auto _ : state) {
    for (int j = 0; j < kParticles; ++j) {
      const Pose2& X = f.X_ML[static_cast<std::size_t>(j)];
      double sum = 0.0;
      for (std::size_t i = 0; i < f.ranges.size(); ++i) {
        const double a = X.theta + f.angles[i];
        const double ex = X.x + f.ranges[i] * std::cos(a), ey = X.y + f.ranges[i] * std::sin(a);
        const int cx = static_cast<int>(std::floor((ex - origin.x()) / kRes));
        const int cy = static_cast<int>(std::floor((ey - origin.y()) / kRes));
        double d = c.max_distance;
        if (cx >= 0 && cy >= 0 && cx < kCells && cy < kCells) {
          d = std::min(d, std::max(0.0, static_cast<double>(f.field.Distance({cx, cy})) - 0.5 * kRes));
        }
        sum += std::log(c.z_hit * norm * std::exp(-d * d / (2 * c.sigma_hit * c.sigma_hit)) +
                        c.z_rand / 30.0);
      }
      log_w[static_cast<std::size_t>(j)] = sum;
    }
    benchmark::DoNotOptimize(log_w.data());
    benchmark::ClobberMemory();
  }
  SetCounters(state, f.ranges.size());
}
BENCHMARK(BM_LikelihoodNaiveReference)->Unit(benchmark::kMicrosecond);

}  // namespace
