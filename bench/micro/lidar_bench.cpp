// LiDAR ray casting throughput: retrace's Lidar::Scan against a Box2D 2.4 b2World::RayCast
// reference over the same geometry, in the same run. The world is a procedurally built office
// block (rooms with doors, merged wall faces, furniture, pillars) plus 30 pedestrians; both
// sides cast full 1081-beam scans from the same fixed list of free poses.
//
//   ./retrace_micro_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
//
// items_per_second is rays per second on one core.

#include <benchmark/benchmark.h>
#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "core/angle.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "sim/lidar.hpp"
#include "sim/ray_caster.hpp"
#include "sim/static_geometry.hpp"

namespace {

using retrace::core::Pose2;
using retrace::core::Rng;
using retrace::core::Vec2;
using retrace::sim::Circle;
using retrace::sim::DynamicCircle;
using retrace::sim::Lidar;
using retrace::sim::LidarConfig;
using retrace::sim::StaticGeometry;

constexpr int kRooms = 36;      // rooms per side
constexpr double kPitch = 6.0;  // m between wall centre lines
constexpr double kWall = 0.2;   // m wall thickness
constexpr double kDoor = 1.0;   // m door width
constexpr int kPoseRooms = 8;   // poses and pedestrians in the central kPoseRooms^2 rooms
constexpr int kPoses = 64;
constexpr int kPedestrians = 30;

struct BenchWorld {
  StaticGeometry geometry;
  std::vector<DynamicCircle> pedestrians;
  std::vector<Pose2> poses;
};

std::vector<Vec2> Rect(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// One wall line (horizontal if `horizontal`, at coordinate `at`): solid intervals along it,
// merged across rooms, broken only by doors and missing walls, each one thick box.
void AddWallLine(StaticGeometry* g, Rng* rng, bool horizontal, double at, bool boundary) {
  std::vector<std::pair<double, double>> gaps;  // along the line
  for (int i = 0; i < kRooms; ++i) {
    const double lo = i * kPitch, hi = (i + 1) * kPitch;
    if (boundary) continue;
    if (rng->Uniform() < 0.2) {  // no wall here: two rooms form a hall
      gaps.emplace_back(lo + kWall / 2.0, hi - kWall / 2.0);
    } else if (rng->Uniform() < 0.85) {
      const double c = rng->Uniform(lo + 1.0, hi - 1.0);
      gaps.emplace_back(c - kDoor / 2.0, c + kDoor / 2.0);
    }
  }
  double start = -kWall / 2.0;
  auto emit = [&](double a, double b) {
    if (b - a < 1e-9) return;
    g->AddPolygon(horizontal ? Rect(a, at - kWall / 2.0, b, at + kWall / 2.0)
                             : Rect(at - kWall / 2.0, a, at + kWall / 2.0, b));
  };
  for (const auto& [a, b] : gaps) {
    emit(start, a);
    start = b;
  }
  emit(start, kRooms * kPitch + kWall / 2.0);
}

bool IsFree(const StaticGeometry& g, const Vec2& p, double clearance) {
  return !g.IsInside(p) && g.Clearance(p) >= clearance;
}

BenchWorld BuildWorld() {
  BenchWorld w;
  Rng rng(20240611);
  for (int j = 0; j <= kRooms; ++j) {
    AddWallLine(&w.geometry, &rng, true, j * kPitch, j == 0 || j == kRooms);
    AddWallLine(&w.geometry, &rng, false, j * kPitch, j == 0 || j == kRooms);
  }
  // Furniture: a rotated cabinet in some rooms, a pillar in others.
  for (int i = 0; i < kRooms; ++i) {
    for (int j = 0; j < kRooms; ++j) {
      const Vec2 c(i * kPitch + rng.Uniform(1.5, kPitch - 1.5),
                   j * kPitch + rng.Uniform(1.5, kPitch - 1.5));
      const double u = rng.Uniform();
      if (u < 0.35) {
        const double a = rng.Uniform(-1.0, 1.0), hx = rng.Uniform(0.3, 0.8), hy = 0.3;
        const Vec2 ex(std::cos(a) * hx, std::sin(a) * hx), ey(-std::sin(a) * hy, std::cos(a) * hy);
        w.geometry.AddPolygon({c - ex - ey, c + ex - ey, c + ex + ey, c - ex + ey});
      } else if (u < 0.55) {
        w.geometry.AddCircle(Circle{c, rng.Uniform(0.15, 0.4)});
      }
    }
  }
  const double lo = (kRooms - kPoseRooms) / 2 * kPitch;
  const double hi = lo + kPoseRooms * kPitch;
  while (static_cast<int>(w.poses.size()) < kPoses) {
    const Vec2 p(rng.Uniform(lo, hi), rng.Uniform(lo, hi));
    if (IsFree(w.geometry, p, 0.5)) {
      w.poses.emplace_back(p.x(), p.y(), rng.Uniform(-retrace::core::kPi, retrace::core::kPi));
    }
  }
  while (static_cast<int>(w.pedestrians.size()) < kPedestrians) {
    const Vec2 p(rng.Uniform(lo, hi), rng.Uniform(lo, hi));
    if (!IsFree(w.geometry, p, 0.35)) continue;
    bool clear = true;
    for (const Pose2& pose : w.poses) clear = clear && (pose.translation() - p).norm() > 0.8;
    if (clear) w.pedestrians.push_back({p, 0.3, static_cast<int>(w.pedestrians.size())});
  }
  return w;
}

const BenchWorld& World() {
  static const BenchWorld world = BuildWorld();
  return world;
}

// ---- Box2D reference ----------------------------------------------------------------------

// Box2D's dynamic tree degrades when long edges have large bounding boxes, so the reference
// can split every edge into pieces of at most `max_piece` m (0: keep the merged edges) to give
// Box2D its best case.
struct Box2dReference {
  b2World world{b2Vec2(0.0f, 0.0f)};
  int fixtures = 0;
  Box2dReference(const BenchWorld& w, double max_piece) {
    b2BodyDef def;
    b2Body* ground = world.CreateBody(&def);
    for (const auto& s : w.geometry.segments()) {
      const double length = (s.b - s.a).norm();
      const int pieces = max_piece > 0.0 ? std::max(1, static_cast<int>(std::ceil(length / max_piece))) : 1;
      for (int k = 0; k < pieces; ++k) {
        const Vec2 a = s.a + (s.b - s.a) * (static_cast<double>(k) / pieces);
        const Vec2 b = s.a + (s.b - s.a) * (static_cast<double>(k + 1) / pieces);
        b2EdgeShape edge;
        edge.SetTwoSided(b2Vec2(static_cast<float>(a.x()), static_cast<float>(a.y())),
                         b2Vec2(static_cast<float>(b.x()), static_cast<float>(b.y())));
        ground->CreateFixture(&edge, 0.0f);
        ++fixtures;
      }
    }
    for (const auto& c : w.geometry.circles()) {
      b2CircleShape circle;
      circle.m_p.Set(static_cast<float>(c.center.x()), static_cast<float>(c.center.y()));
      circle.m_radius = static_cast<float>(c.radius);
      ground->CreateFixture(&circle, 0.0f);
    }
    // Pedestrians as dynamic bodies, as the simulator holds them.
    for (const auto& p : w.pedestrians) {
      b2BodyDef body_def;
      body_def.type = b2_dynamicBody;
      body_def.position.Set(static_cast<float>(p.center.x()), static_cast<float>(p.center.y()));
      b2Body* body = world.CreateBody(&body_def);
      b2CircleShape circle;
      circle.m_radius = static_cast<float>(p.radius);
      body->CreateFixture(&circle, 1.0f);
    }
  }
};

// Closest hit: clip the ray to every reported fraction.
class ClosestHit : public b2RayCastCallback {
 public:
  float ReportFixture(b2Fixture*, const b2Vec2&, const b2Vec2&, float fraction) override {
    fraction_ = fraction;
    return fraction;
  }
  void Reset() { fraction_ = 2.0f; }
  float fraction() const { return fraction_; }

 private:
  float fraction_ = 2.0f;
};

const Box2dReference& Reference(double max_piece) {
  static std::map<double, std::unique_ptr<Box2dReference>> cache;
  auto& ref = cache[max_piece];
  if (!ref) ref = std::make_unique<Box2dReference>(World(), max_piece);
  return *ref;
}

// Beam directions in W for a scan from X_WL, as the Lidar computes them.
void BeamDirections(const LidarConfig& config, const Pose2& X_WL, std::vector<Vec2>* dirs) {
  const double fov = retrace::core::DegToRad(config.fov_deg);
  const double inc = fov / (config.beams - 1);
  dirs->resize(static_cast<std::size_t>(config.beams));
  for (int i = 0; i < config.beams; ++i) {
    const double a = X_WL.theta - 0.5 * fov + i * inc;
    (*dirs)[static_cast<std::size_t>(i)] = Vec2(std::cos(a), std::sin(a));
  }
}

double Box2dRange(const Box2dReference& ref, ClosestHit* hit, const Vec2& o, const Vec2& d,
                  double range_max) {
  const b2Vec2 p1(static_cast<float>(o.x()), static_cast<float>(o.y()));
  const b2Vec2 p2(static_cast<float>(o.x() + range_max * d.x()),
                  static_cast<float>(o.y() + range_max * d.y()));
  hit->Reset();
  ref.world.RayCast(hit, p1, p2);
  return hit->fraction() <= 1.0f ? hit->fraction() * range_max
                                 : std::numeric_limits<double>::infinity();
}

void AddWorldCounters(benchmark::State& state) {
  const BenchWorld& w = World();
  state.counters["edges"] = static_cast<double>(w.geometry.segments().size());
  state.counters["circles"] = static_cast<double>(w.geometry.circles().size());
  state.counters["pedestrians"] = static_cast<double>(w.pedestrians.size());
}

// ---- Benchmarks ---------------------------------------------------------------------------

void BM_RetraceLidarScan(benchmark::State& state) {
  const BenchWorld& w = World();
  const LidarConfig config;  // UTM-30LX defaults, noise on
  const Lidar lidar(config, w.geometry);
  Rng rng(7);
  std::size_t k = 0;
  for (auto _ : state) {
    const auto reading = lidar.Scan(w.poses[k++ % w.poses.size()], w.pedestrians, 0.0, rng);
    benchmark::DoNotOptimize(reading.scan.ranges.data());
  }
  state.SetItemsProcessed(state.iterations() * config.beams);
  AddWorldCounters(state);
  state.counters["grid_cells"] =
      static_cast<double>(lidar.ray_caster().grid_width()) * lidar.ray_caster().grid_height();
  state.counters["cell_m"] = lidar.ray_caster().cell_size();
}
BENCHMARK(BM_RetraceLidarScan)->Unit(benchmark::kMicrosecond);

// The argument is the longest edge piece given to Box2D in cm (0: the merged edges as they are).
void BM_Box2dRayCastScan(benchmark::State& state) {
  const BenchWorld& w = World();
  const Box2dReference& ref = Reference(static_cast<double>(state.range(0)) / 100.0);
  const LidarConfig config;
  ClosestHit hit;
  // Beam directions are precomputed so that only the casts are timed.
  std::vector<std::vector<Vec2>> fans(w.poses.size());
  for (std::size_t p = 0; p < w.poses.size(); ++p) BeamDirections(config, w.poses[p], &fans[p]);
  std::vector<double> ranges(static_cast<std::size_t>(config.beams));
  std::size_t k = 0;
  for (auto _ : state) {
    const std::size_t p = k++ % w.poses.size();
    const Pose2& X_WL = w.poses[p];
    const std::vector<Vec2>& dirs = fans[p];
    for (std::size_t i = 0; i < dirs.size(); ++i) {
      ranges[i] = Box2dRange(ref, &hit, X_WL.translation(), dirs[i], config.range_max);
    }
    benchmark::DoNotOptimize(ranges.data());
  }
  state.SetItemsProcessed(state.iterations() * config.beams);
  AddWorldCounters(state);

  // Agreement with retrace (noise off), as a sanity check of the comparison: the fraction of
  // beams whose ranges differ by more than 1 mm (Box2D works in float).
  LidarConfig exact;
  exact.noise = {0.0, 0.0, 0.0, 0.0};
  const Lidar lidar(exact, w.geometry);
  Rng rng(1);
  double mismatches = 0.0, total = 0.0, range_sum = 0.0, range_count = 0.0;
  for (std::size_t p = 0; p < w.poses.size(); ++p) {
    const Pose2& pose = w.poses[p];
    const auto reading = lidar.Scan(pose, w.pedestrians, 0.0, rng);
    for (std::size_t i = 0; i < fans[p].size(); ++i) {
      const double ours = reading.truth[i].range;
      const double theirs = Box2dRange(ref, &hit, pose.translation(), fans[p][i], config.range_max);
      const bool same = (std::isinf(ours) && std::isinf(theirs)) || std::abs(ours - theirs) < 1e-3;
      mismatches += same ? 0.0 : 1.0;
      if (std::isfinite(ours)) {
        range_sum += ours;
        range_count += 1.0;
      }
      total += 1.0;
    }
  }
  state.counters["mismatch_frac"] = mismatches / total;
  state.counters["mean_range_m"] = range_sum / range_count;
  state.counters["tree_height"] = ref.world.GetTreeHeight();
  state.counters["tree_quality"] = ref.world.GetTreeQuality();
  state.counters["box2d_edges"] = ref.fixtures;
}
BENCHMARK(BM_Box2dRayCastScan)->Unit(benchmark::kMicrosecond)->Arg(0)->Arg(100)->Arg(300)->Arg(600);

// Static geometry only, no noise and no pedestrians: the ray caster alone, for a grid cell
// size (cm) given as the argument (0: automatic).
void BM_RetraceRayCasterFan(benchmark::State& state) {
  const BenchWorld& w = World();
  const LidarConfig config;
  const retrace::sim::RayCaster caster(w.geometry, static_cast<double>(state.range(0)) / 100.0);
  std::vector<std::vector<Vec2>> fans(w.poses.size());
  for (std::size_t p = 0; p < w.poses.size(); ++p) BeamDirections(config, w.poses[p], &fans[p]);
  std::vector<double> limits(static_cast<std::size_t>(config.beams), config.range_max);
  std::vector<double> out(limits.size());
  std::size_t k = 0, in_wedges = 0;
  for (auto _ : state) {
    const std::size_t p = k++ % w.poses.size();
    in_wedges += caster.CastFan(w.poses[p].translation(), fans[p], limits, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * config.beams);
  // The share of rays cast together in wedges (the rest walk the grid one by one).
  state.counters["wedge_frac"] =
      static_cast<double>(in_wedges) / static_cast<double>(state.iterations() * config.beams);
  state.counters["cell_m"] = caster.cell_size();
  state.counters["entries"] = static_cast<double>(caster.entry_count());
}
BENCHMARK(BM_RetraceRayCasterFan)
    ->Unit(benchmark::kMicrosecond)
    ->Arg(0)
    ->Arg(50)
    ->Arg(100)
    ->Arg(300);

}  // namespace
