// Resampling: retrace's low-variance (systematic) resampling, O(N), against multinomial
// resampling by linear search of the cumulative weights, O(N²) (what the original
// implementation did), in the same run.
//
//   ./retrace_micro_bench --benchmark_filter=Resampl --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// The complexity rows (BigO, RMS) fit the time against N.

#include <benchmark/benchmark.h>

#include <vector>

#include "core/rng.hpp"
#include "nav/resampling.hpp"

namespace {

std::vector<double> RandomWeights(std::size_t n) {
  retrace::core::Rng rng(n);
  std::vector<double> w(n);
  double sum = 0.0;
  for (double& x : w) sum += (x = rng.Uniform() * rng.Uniform());
  for (double& x : w) x /= sum;
  return w;
}

void BM_ResamplingLowVariance(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const std::vector<double> w = RandomWeights(n);
  retrace::core::Rng rng(1);
  for (auto _ : state) {
    std::vector<std::size_t> idx = retrace::nav::LowVarianceResample(w, n, rng);
    benchmark::DoNotOptimize(idx.data());
  }
  state.SetComplexityN(state.range(0));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_ResamplingLowVariance)
    ->RangeMultiplier(10)
    ->Range(1000, 100000)
    ->Complexity(benchmark::oN)
    ->Unit(benchmark::kMicrosecond);

void BM_ResamplingMultinomialLinearReference(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const std::vector<double> w = RandomWeights(n);
  retrace::core::Rng rng(1);
  for (auto _ : state) {
    std::vector<std::size_t> idx(n);
    for (std::size_t m = 0; m < n; ++m) {
      const double u = rng.Uniform();
      double c = 0.0;
      std::size_t i = 0;
      while (i + 1 < n && (c += w[i]) <= u) ++i;
      idx[m] = i;
    }
    benchmark::DoNotOptimize(idx.data());
  }
  state.SetComplexityN(state.range(0));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_ResamplingMultinomialLinearReference)
    ->RangeMultiplier(10)
    ->Range(1000, 10000)
    ->Complexity(benchmark::oNSquared)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
