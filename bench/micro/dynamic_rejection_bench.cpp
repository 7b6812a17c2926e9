// The dynamic scan point test (eq. 7-9) for one localizer update: 500 particles x 108 beams,
// each needing the expected range of its ray on the map, on the procedurally generated
// 300 m x 300 m campus at 0.1 m of likelihood_bench.cpp with a 30 m LiDAR and pedestrians
// shortening 20 % of the beams. Four implementations in the same run:
//
//   Bounds             retrace's TestDynamicBeams as the localizer calls it: a beam decided as
//                      soon as bounds on eq. (9)'s sums settle it (a sample of 32 particles cast
//                      exactly, then every ray cast to 0.6 m beyond the reading), the exact sums
//                      of SphereTracing otherwise
//   SphereTracing      TestDynamicBeams with every ratio (GridRayCaster::CastMany: a provably clear
//                      common start per bundle of 32 rays of similar heading, then sphere
//                      tracing on an exact clearance grid and the exact traversal over the last
//                      cells, many rays in lockstep; BeamModel::SumTerms)
//   PerCellReference   the straightforward reference of the issue, written here: per particle
//                      and beam an Amanatides-Woo traversal of the occupancy grid's cells,
//                      testing each cell's log-odds against the occupied threshold, then
//                      BeamModel::Evaluate
//   TightDda           TestDynamicBeams with GridRayCaster::CastDda, retrace's own per-cell
//                      traversal of the precomputed one-byte occupancy mask
//
// All must give the same mask: `mismatches` counts beams whose classification differs from
// SphereTracing's (and `ratio_mismatches` beams whose ratio differs in any bit, of those with a
// ratio: Bounds computes it only for the `exact_beams` that its bounds do not decide); both must
// be 0.
//
//   ./retrace_micro_bench --benchmark_filter=Dynamic --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "bench/micro/campus_map.hpp"
#include "core/angle.hpp"
#include "core/laser_scan.hpp"
#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "nav/beam_model.hpp"
#include "nav/dynamic_beam_test.hpp"
#include "nav/grid_ray_caster.hpp"
#include "nav/likelihood_field.hpp"

namespace {

using retrace::core::Pose2;
using retrace::core::Rng;
using retrace::nav::BeamModel;
using retrace::nav::DynamicBeamResult;
using retrace::nav::RayCastMethod;

constexpr int kParticles = 500;

struct Fixture {
  retrace::core::OccupancyGrid map = retrace::bench_micro::CampusMap();
  retrace::nav::LikelihoodField field{map, {}, 30.0};
  retrace::nav::GridRayCaster caster{field};
  BeamModel model{{}, 30.0};
  retrace::core::LaserScan scan;
  std::vector<Pose2> X_ML;
  std::vector<int> beams;
  int pedestrian_beams = 0;

  Fixture() {
    Rng rng(11);
    const Pose2 truth = retrace::bench_micro::FreeCampusPose(map, field, rng);
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

// The start cell of a traversal on one axis at ray parameter t: a floor guess, settled by the
// crossings (cell i spans [cross(i), cross(i + 1)) going up, [cross(i + 1), cross(i)) going
// down) so that the traversal agrees with its own crossings. -1 or n when outside.
template <class Cross>
int StartCell(double t, double p, double d, double o, double res, int step, int n, Cross cross) {
  if (step == 0) {
    const double g = std::floor((p - o) / res);
    return g < 0.0 ? -1 : (g >= n ? n : static_cast<int>(g));
  }
  const double g = std::floor((p + t * d - o) * (1.0 / res));
  int i = g < -1.0 ? -1 : (g > n ? n : static_cast<int>(g));
  if (step > 0) {
    while (i >= 0 && cross(i) > t) --i;
    while (i < n && cross(i + 1) <= t) ++i;
  } else {
    while (i < n && cross(i + 1) > t) ++i;
    while (i >= 0 && cross(i) <= t) --i;
  }
  return std::clamp(i, -1, n);
}

// The straightforward reference ray cast: Amanatides-Woo on the occupancy grid. The ray visits
// every cell it passes through; a cell is occupied when its log-odds reach the logit of the
// occupied threshold. Boundary crossings are computed in closed form, t = (boundary - start) /
// direction, as GridRayCaster does, so the cells and the range are exactly CastDda's. Returns
// the t (m) at which the ray enters the first occupied cell, or +inf.
double ReferenceCast(const retrace::core::OccupancyGrid& map, double occupied_log_odds, double x,
                     double y, double dx, double dy, double range_max) {
  const double inf = std::numeric_limits<double>::infinity();
  const double ox = map.origin().x(), oy = map.origin().y(), res = map.resolution();
  const int width = map.width(), height = map.height();
  const int sx = dx > 1e-12 ? 1 : (dx < -1e-12 ? -1 : 0);
  const int sy = dy > 1e-12 ? 1 : (dy < -1e-12 ? -1 : 0);
  const double inv_dx = sx != 0 ? 1.0 / dx : 0.0, inv_dy = sy != 0 ? 1.0 / dy : 0.0;
  const auto tx = [&](int i) { return (ox + static_cast<double>(i) * res - x) * inv_dx; };
  const auto ty = [&](int i) { return (oy + static_cast<double>(i) * res - y) * inv_dy; };
  // Clip to the map: inside for t in [t_lo, t_exit).
  double t_lo = 0.0, t_exit = inf;
  if (sx == 0) {
    if (!(x >= ox && x < ox + width * res)) return inf;
  } else {
    t_lo = std::max(t_lo, sx > 0 ? tx(0) : tx(width));
    t_exit = std::min(t_exit, sx > 0 ? tx(width) : tx(0));
  }
  if (sy == 0) {
    if (!(y >= oy && y < oy + height * res)) return inf;
  } else {
    t_lo = std::max(t_lo, sy > 0 ? ty(0) : ty(height));
    t_exit = std::min(t_exit, sy > 0 ? ty(height) : ty(0));
  }
  if (t_lo > range_max || t_lo >= t_exit) return inf;
  int ix = StartCell(t_lo, x, dx, ox, res, sx, width, tx);
  int iy = StartCell(t_lo, y, dy, oy, res, sy, height, ty);
  if (ix < 0 || iy < 0 || ix >= width || iy >= height) return inf;
  double next_x = sx > 0 ? tx(ix + 1) : (sx < 0 ? tx(ix) : inf);
  double next_y = sy > 0 ? ty(iy + 1) : (sy < 0 ? ty(iy) : inf);
  double t_enter = t_lo;
  while (true) {
    if (static_cast<double>(map.LogOdds({ix, iy})) >= occupied_log_odds) return t_enter;
    if (next_x < next_y) {
      t_enter = next_x;
      ix += sx;
      if (ix < 0 || ix >= width) return inf;
      next_x = sx > 0 ? tx(ix + 1) : tx(ix);
    } else {
      t_enter = next_y;
      iy += sy;
      if (iy < 0 || iy >= height) return inf;
      next_y = sy > 0 ? ty(iy + 1) : ty(iy);
    }
    if (t_enter > range_max) return inf;
  }
}

// The straightforward dynamic-point test (eq. 9, equal weights): per beam, per particle the
// beam's direction rotated by the particle's heading, the reference ray cast and the beam model.
void ReferenceDynamicBeams(const Fixture& f, double chi, DynamicBeamResult* result) {
  const double occupied_log_odds = retrace::core::Logit(f.field.config().occupied_threshold);
  const double range_max = f.model.range_max();
  result->dynamic.assign(f.beams.size(), 0);
  result->ratio.assign(f.beams.size(), 0.0);
  for (std::size_t b = 0; b < f.beams.size(); ++b) {
    const std::size_t i = static_cast<std::size_t>(f.beams[b]);
    const double z = f.scan.ranges[i];
    const double ux = std::cos(f.scan.Angle(i)), uy = std::sin(f.scan.Angle(i));
    double sum_short = 0.0, sum_total = 0.0;
    for (const Pose2& X : f.X_ML) {
      const double c = std::cos(X.theta), s = std::sin(X.theta);
      const double z_star =
          ReferenceCast(f.map, occupied_log_odds, X.x, X.y, c * ux - s * uy, s * ux + c * uy, range_max);
      const BeamModel::Terms t = f.model.Evaluate(z, z_star);
      sum_short += t.short_part;
      sum_total += t.total;
    }
    result->ratio[b] = sum_total > 0.0 ? sum_short / sum_total : 0.0;
    result->dynamic[b] = result->ratio[b] > chi ? 1 : 0;
  }
}

enum class Method { kBounds, kSphereTracing, kPerCellReference, kTightDda };

void RunOnce(const Fixture& f, Method method, DynamicBeamResult* result) {
  if (method == Method::kPerCellReference) {
    ReferenceDynamicBeams(f, 0.9, result);
    return;
  }
  retrace::nav::DynamicTestOptions options;
  options.method =
      method == Method::kTightDda ? RayCastMethod::kDda : RayCastMethod::kSphereTracing;
  options.decide_by_bounds = method == Method::kBounds;
  retrace::nav::TestDynamicBeams(f.model, f.caster, f.X_ML, {}, f.scan, f.beams, 0.9, options,
                                 result);
}

void Run(benchmark::State& state, Method method) {
  const Fixture& f = GetFixture();
  DynamicBeamResult result, ours, mine;
  // The check, outside the timed loop: this method gives the same ratios and mask as ours.
  RunOnce(f, Method::kSphereTracing, &ours);
  RunOnce(f, method, &mine);
  int mismatches = 0, ratio_mismatches = 0, dynamic = 0, exact_beams = 0;
  for (std::size_t b = 0; b < f.beams.size(); ++b) {
    mismatches += mine.dynamic[b] != ours.dynamic[b] ? 1 : 0;
    dynamic += mine.dynamic[b];
    if (std::isnan(mine.ratio[b])) continue;  // decided by bounds
    ++exact_beams;
    ratio_mismatches +=
        std::bit_cast<std::uint64_t>(mine.ratio[b]) != std::bit_cast<std::uint64_t>(ours.ratio[b])
            ? 1
            : 0;
  }
  for (auto _ : state) {
    RunOnce(f, method, &result);
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
  state.counters["exact_beams"] = exact_beams;
}

void BM_DynamicRejectionBounds(benchmark::State& state) { Run(state, Method::kBounds); }
BENCHMARK(BM_DynamicRejectionBounds)->Unit(benchmark::kMillisecond);

void BM_DynamicRejectionSphereTracing(benchmark::State& state) { Run(state, Method::kSphereTracing); }
BENCHMARK(BM_DynamicRejectionSphereTracing)->Unit(benchmark::kMillisecond);

void BM_DynamicRejectionPerCellReference(benchmark::State& state) {
  Run(state, Method::kPerCellReference);
}
BENCHMARK(BM_DynamicRejectionPerCellReference)->Unit(benchmark::kMillisecond);

void BM_DynamicRejectionTightDda(benchmark::State& state) { Run(state, Method::kTightDda); }
BENCHMARK(BM_DynamicRejectionTightDda)->Unit(benchmark::kMillisecond);

}  // namespace
