// Checking a route's switch points (bench/engine/switch_points.cpp): the revisit search of every
// sample of the route goes through a grid over its segments (core/path_index.hpp), so a route
// that never revisits itself, the worst case (every sample searches all the road behind it), is
// checked in time linear in its length.
//
//   ./retrace_micro_bench --benchmark_filter=SwitchPoints
//
// The complexity rows (BigO, RMS) fit the time against the route length in metres.

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "bench/engine/switch_points.hpp"

namespace {

// An Archimedean spiral of `length` metres with its arms 10 m apart and a point every metre:
// it comes no closer to itself than 10 m, so with a 3 m radius no sample is a revisit.
std::vector<retrace::core::Vec2> Spiral(double length) {
  constexpr double kSpacing = 10.0;
  const double a = kSpacing / (2.0 * std::numbers::pi);
  std::vector<retrace::core::Vec2> route;
  double theta = 2.0 * std::numbers::pi;  // from one arm out, not from the centre's tight turns
  for (double s = 0.0; s <= length; s += 1.0) {
    route.emplace_back(a * theta * std::cos(theta), a * theta * std::sin(theta));
    theta += 1.0 / (a * std::hypot(1.0, theta));  // 1 m of arc length
  }
  return route;
}

void BM_CheckSwitchPointsOfASpiral(benchmark::State& state) {
  const std::vector<retrace::core::Vec2> route = Spiral(static_cast<double>(state.range(0)));
  for (auto _ : state) {
    auto warnings = retrace::bench::CheckSwitchPoints(route, {}, 3.0);
    if (!warnings.empty()) state.SkipWithError("the spiral revisits itself");
    benchmark::DoNotOptimize(warnings.data());
  }
  state.SetComplexityN(state.range(0));
  state.SetItemsProcessed(state.iterations() * state.range(0));  // metres of route
}
BENCHMARK(BM_CheckSwitchPointsOfASpiral)
    ->RangeMultiplier(10)
    ->Range(1000, 100000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oN);

}  // namespace
