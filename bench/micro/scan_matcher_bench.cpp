// The teaching drive's scan matcher (nav/scan_matcher.hpp) per keyframe: matching a full
// 1081-beam scan (270°, 30 m, 2 cm range noise) against a map of the 20 keyframes before it,
// then adding it to the map, on the procedurally generated campus of the likelihood benchmark.
// The keyframes walk 0.5 m apart through free space; the prediction is 3 cm and 0.3° off.
//
//   ./retrace_micro_bench --benchmark_filter=ScanMatcher --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
//
// The budget (issue 14): 2 ms per keyframe on one core.

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "bench/micro/campus_map.hpp"
#include "core/angle.hpp"
#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "nav/grid_ray_caster.hpp"
#include "nav/likelihood_field.hpp"
#include "nav/scan_matcher.hpp"

namespace {

using retrace::core::Pose2;

constexpr int kKeyframes = 21;  // 20 in the map, the last one matched

struct Fixture {
  std::vector<Pose2> poses;
  std::vector<retrace::core::LaserScan> scans;
  Pose2 predicted;

  Fixture() {
    retrace::bench_micro::CampusDrive drive =
        retrace::bench_micro::DriveThroughCampus(kKeyframes, 0.05, 11);
    poses = std::move(drive.poses);
    scans = std::move(drive.scans);
    const Pose2& last = poses.back();
    predicted = Pose2(last.x + 0.03, last.y - 0.02, last.theta + retrace::core::DegToRad(0.3));
  }
};

const Fixture& GetFixture() {
  static const Fixture f;
  return f;
}

retrace::nav::ScanMatcher MatcherWithMap(const Fixture& f) {
  retrace::nav::ScanMatcher matcher({}, {});
  for (int k = 0; k + 1 < kKeyframes; ++k)
    matcher.AddScan(f.scans[static_cast<std::size_t>(k)], f.poses[static_cast<std::size_t>(k)]);
  return matcher;
}

// Match + AddScan of one keyframe: what the teach recorder does per keyframe.
void BM_ScanMatcherKeyframe(benchmark::State& state) {
  const Fixture& f = GetFixture();
  const retrace::nav::ScanMatcher base = MatcherWithMap(f);
  double error_m = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    retrace::nav::ScanMatcher matcher = base;
    state.ResumeTiming();
    const retrace::nav::ScanMatch m = matcher.Match(f.scans.back(), f.predicted);
    matcher.AddScan(f.scans.back(), m.X_MR);
    error_m = retrace::core::Distance(m.X_MR, f.poses.back());
    benchmark::DoNotOptimize(m);
  }
  state.counters["error_mm"] = 1000.0 * error_m;
  state.counters["map_points"] = static_cast<double>(base.size());
}
BENCHMARK(BM_ScanMatcherKeyframe)->Unit(benchmark::kMillisecond);

// Match alone.
void BM_ScanMatcherMatch(benchmark::State& state) {
  const Fixture& f = GetFixture();
  retrace::nav::ScanMatcher matcher = MatcherWithMap(f);
  for (auto _ : state) {
    const retrace::nav::ScanMatch m = matcher.Match(f.scans.back(), f.predicted);
    benchmark::DoNotOptimize(m);
  }
}
BENCHMARK(BM_ScanMatcherMatch)->Unit(benchmark::kMillisecond);

}  // namespace
