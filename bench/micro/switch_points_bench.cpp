// The revisit search behind CheckSwitchPoints (bench/engine/switch_points.cpp): every sample of a
// route, 3/8 m apart, looks for the road more than 3 radii behind it within the revisit radius.
// Through the grid over the route's segments (core/path_index.hpp) that costs the segments near
// the sample; by a scan of the road behind it (core::ProjectOntoPath, what CheckSwitchPoints did
// before 2026-11-26) it costs all of them, so the check grows with the square of the length.
//
//   ./retrace_micro_bench --benchmark_filter=RevisitSearch
//
// The route is the worst case: an Archimedean spiral with arms 10 m apart and a point every
// metre, which never comes within the 3 m radius of itself, so no search stops early. The
// complexity rows (BigO, RMS) fit the time against the route length in metres.

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/path_index.hpp"
#include "core/path_projection.hpp"

namespace {

using retrace::core::Vec2;

constexpr double kRadius = 3.0;          // m, route.revisit_radius
constexpr double kStep = kRadius / 8.0;  // m between the samples, as CheckSwitchPoints
constexpr double kLag = 3.0 * kRadius;   // m of road just behind a sample that it ignores

std::vector<Vec2> Spiral(double length) {
  constexpr double kSpacing = 10.0;
  const double a = kSpacing / (2.0 * std::numbers::pi);
  std::vector<Vec2> route;
  double theta = 2.0 * std::numbers::pi;  // from one arm out, not from the centre's tight turns
  for (double s = 0.0; s <= length; s += 1.0) {
    route.emplace_back(a * theta * std::cos(theta), a * theta * std::sin(theta));
    theta += 1.0 / (a * std::hypot(1.0, theta));  // 1 m of arc length
  }
  return route;
}

// The samples of the route (interpolated positions every kStep m) and their arc lengths.
struct Samples {
  std::vector<Vec2> p;
  std::vector<double> s;
};
Samples Sample(const std::vector<Vec2>& route, const std::vector<double>& arc) {
  Samples out;
  std::size_t i = 0;
  for (double s = 0.0; s <= arc.back(); s += kStep) {
    while (i + 2 < arc.size() && arc[i + 1] < s) ++i;
    const double t = (s - arc[i]) / (arc[i + 1] - arc[i]);
    out.p.push_back(route[i] + t * (route[i + 1] - route[i]));
    out.s.push_back(s);
  }
  return out;
}

template <typename Search>
void RevisitSearch(benchmark::State& state, Search search) {
  const std::vector<Vec2> route = Spiral(static_cast<double>(state.range(0)));
  const std::vector<double> arc = retrace::core::CumulativeArcLength(route);
  const Samples samples = Sample(route, arc);
  for (auto _ : state) {
    const retrace::core::PathIndex index(route, arc, kRadius);  // built once per check
    int revisits = 0;
    for (std::size_t k = 0; k < samples.p.size(); ++k) {
      if (samples.s[k] <= kLag) continue;
      revisits += search(index, route, arc, samples.p[k], samples.s[k] - kLag) < kRadius ? 1 : 0;
    }
    if (revisits != 0) state.SkipWithError("the spiral revisits itself");
    benchmark::DoNotOptimize(revisits);
  }
  state.SetComplexityN(state.range(0));
  state.SetItemsProcessed(state.iterations() * state.range(0));  // metres of route
}

void BM_RevisitSearchGrid(benchmark::State& state) {
  RevisitSearch(state, [](const retrace::core::PathIndex& index, const std::vector<Vec2>&,
                          const std::vector<double>&, const Vec2& p,
                          double s_hi) { return index.Project(p, 0.0, s_hi).distance; });
}
BENCHMARK(BM_RevisitSearchGrid)
    ->RangeMultiplier(10)
    ->Range(1000, 100000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oN);

void BM_RevisitSearchScan(benchmark::State& state) {
  RevisitSearch(state, [](const retrace::core::PathIndex&, const std::vector<Vec2>& route,
                          const std::vector<double>& arc, const Vec2& p, double s_hi) {
    return retrace::core::ProjectOntoPath(route, arc, p, 0.0, s_hi).distance;
  });
}
BENCHMARK(BM_RevisitSearchScan)
    ->RangeMultiplier(10)
    ->Range(1000, 10000)  // 100 km would take minutes
    ->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oNSquared);

}  // namespace
