#include "bench/crowd/fundamental_diagram.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "bench/crowd/closest_approach.hpp"
#include "core/errors.hpp"
#include "core/format.hpp"
#include "core/rng.hpp"
#include "io/config_yaml.hpp"
#include "sim/physics_world.hpp"
#include "sim/static_geometry.hpp"

namespace retrace::bench {
namespace {

using core::Vec2;

// Thickness (m) of the outer wall's segments.
constexpr double kWallThickness = 0.3;
// Start points keep this far (m) inside the walk planner's free band: the free test is made at
// the centres of its cells, up to half a cell diagonal away.
constexpr double kCellSlack = 0.75;  // of a cell size
// Largest half-size (m) of the box each start point is drawn from.
constexpr double kMaxJitter = 0.05;
// Most lattice rows tried across the corridor.
constexpr int kMaxRows = 40;

sim::StaticGeometry RingGeometry(const FundamentalDiagramConfig& c) {
  sim::StaticGeometry g;
  g.AddCircle({Vec2(0.0, 0.0), c.inner_radius});
  // The polygon circumscribes the outer radius, so that the walkable area is at least
  // pi (R_out² - R_in²) (less than 0.1 % more with 96 segments).
  const int m = c.wall_segments;
  const double r0 = c.outer_radius() / std::cos(core::kPi / m);
  const double r1 = r0 + kWallThickness;
  for (int i = 0; i < m; ++i) {
    const double a0 = 2.0 * core::kPi * i / m;
    const double a1 = 2.0 * core::kPi * (i + 1) / m;
    const Vec2 u0(std::cos(a0), std::sin(a0));
    const Vec2 u1(std::cos(a1), std::sin(a1));
    g.AddPolygon({r0 * u0, r0 * u1, r1 * u1, r1 * u0});
  }
  return g;
}

struct Lattice {
  std::vector<Vec2> sites;
  double spacing = 0.0;  // closest distance between two sites (m)
};

double MinDistance(const std::vector<Vec2>& sites) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < sites.size(); ++i) {
    for (std::size_t j = i + 1; j < sites.size(); ++j)
      best = std::min(best, (sites[i] - sites[j]).squaredNorm());
  }
  return std::sqrt(best);
}

// `n` start points on rows (concentric circles) from radius a to b, as many per row as its
// share of the rows' total length, every other row turned by half a spacing: the row count
// with the largest closest distance wins.
Lattice RingLattice(int n, double a, double b, double phase) {
  Lattice best;
  best.spacing = -1.0;
  for (int rows = 1; rows <= kMaxRows && rows <= n; ++rows) {
    std::vector<double> radii;
    for (int k = 0; k < rows; ++k)
      radii.push_back(rows == 1 ? 0.5 * (a + b) : a + (b - a) * k / (rows - 1));
    double total = 0.0;
    for (double r : radii) total += r;
    std::vector<int> per_row;
    int placed = 0;
    for (double r : radii) {
      per_row.push_back(static_cast<int>(std::floor(n * r / total)));
      placed += per_row.back();
    }
    for (int k = rows - 1; placed < n; k = (k + rows - 1) % rows) {  // outer rows first
      ++per_row[static_cast<std::size_t>(k)];
      ++placed;
    }
    Lattice l;
    for (int k = 0; k < rows; ++k) {
      const int m = per_row[static_cast<std::size_t>(k)];
      const double offset = phase + (k % 2 == 0 ? 0.0 : core::kPi / std::max(1, m));
      for (int i = 0; i < m; ++i) {
        const double angle = offset + 2.0 * core::kPi * i / m;
        l.sites.push_back(radii[static_cast<std::size_t>(k)] *
                          Vec2(std::cos(angle), std::sin(angle)));
      }
    }
    l.spacing = l.sites.size() < 2 ? b - a + 1.0 : MinDistance(l.sites);
    if (l.spacing > best.spacing) best = std::move(l);
  }
  return best;
}

// The loop waypoint Pedestrians starts person `person` (a group of one) at: its draws replayed
// (desired speed, one start point from the box, then the index). Should the start point need a
// second try, the guess is off and that person walks to a random waypoint first (counted).
std::uint64_t FirstLoopIndex(const core::Rng& crowd_rng, std::size_t person,
                             const sim::PedestrianGroupConfig& group, int waypoints) {
  core::Rng w = crowd_rng.Split(static_cast<std::uint64_t>(person));
  (void)w.Normal(group.speed_mean, group.speed_std);
  (void)w.Uniform(group.region_min.x(), group.region_max.x());
  (void)w.Uniform(group.region_min.y(), group.region_max.y());
  return w.UniformIndex(static_cast<std::uint64_t>(waypoints));
}

// The row's pedestrian count (at least two) and the density it gives, with Weidmann's speed there.
FundamentalDiagramRow RowForDensity(const FundamentalDiagramConfig& config, double density) {
  FundamentalDiagramRow row;
  row.requested_density = density;
  const double area = config.area();
  row.count = std::max(2, static_cast<int>(std::lround(density * area)));
  row.density = row.count / area;
  row.weidmann_speed = WeidmannSpeed(row.density);
  return row;
}

// The radii (m) the lanes (loop waypoints) lie between: this far inside the walls, so that the
// walk planner finds them free; start points stay a jitter further in.
struct LaneBand {
  double min = 0.0;
  double max = 0.0;
};

LaneBand LaneBandOf(const FundamentalDiagramConfig& config) {
  const double inset = config.pedestrian_radius + config.crowd.planner.margin +
                       kCellSlack * config.crowd.planner.cell_size;
  return {config.inner_radius + inset, config.outer_radius() - inset};
}

// Directions (+1 counter-clockwise, -1 clockwise): a random floor(fraction x sites) of the sites
// walks clockwise.
std::vector<int> RandomDirections(std::size_t sites, double clockwise_fraction, core::Rng& layout) {
  std::vector<int> direction(sites, 1);
  std::vector<std::size_t> order(sites);
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  for (std::size_t i = order.size(); i > 1; --i)
    std::swap(order[i - 1], order[layout.UniformIndex(i)]);
  const auto clockwise =
      static_cast<std::size_t>(std::floor(clockwise_fraction * static_cast<double>(sites) + 1e-9));
  for (std::size_t k = 0; k < clockwise; ++k) direction[order[k]] = -1;
  return direction;
}

// The crowd of the ring: one group per person, and the waypoint each is meant to head for first.
struct RingGroups {
  std::vector<sim::PedestrianGroupConfig> groups;
  std::vector<Vec2> first_goals;
};

// One group per person: its start box round its site and a loop of waypoints on a lane of its
// own, in its direction.
RingGroups RingWalkers(const FundamentalDiagramConfig& config, const Lattice& lattice,
                       const std::vector<int>& direction, double jitter, const LaneBand& lanes,
                       core::Rng& layout, const core::Rng& crowd_rng) {
  RingGroups ring;
  for (std::size_t i = 0; i < lattice.sites.size(); ++i) {
    const Vec2& site = lattice.sites[i];
    // Everyone keeps to a lane of their own, drawn across the corridor: with the lattice rows as
    // lanes, two people walking towards each other on one row would meet exactly head-on, where
    // the model's repulsion has no sideways part and both stop until the progress check makes
    // one step aside.
    const double lane = layout.Uniform(lanes.min, lanes.max);
    const double angle0 = std::atan2(site.y(), site.x());
    sim::PedestrianGroupConfig g;
    g.count = 1;
    g.region_min = site - Vec2(jitter, jitter);
    g.region_max = site + Vec2(jitter, jitter);
    g.mode = sim::PedestrianMode::kLoop;
    g.speed_mean = config.speed_mean;
    g.speed_std = config.speed_std;
    g.radius = config.pedestrian_radius;
    // Pedestrians starts a loop at a random waypoint of it; the waypoint that draw picks is
    // made the first one ahead, so that nobody walks half the ring the wrong way first.
    const auto first = static_cast<int>(FirstLoopIndex(crowd_rng, i, g, config.waypoints));
    for (int k = 0; k < config.waypoints; ++k) {
      const int ahead = 1 + (k - first + config.waypoints) % config.waypoints;
      const double a = angle0 + direction[i] * 2.0 * core::kPi * ahead / config.waypoints;
      g.waypoints.push_back(lane * Vec2(std::cos(a), std::sin(a)));
    }
    ring.first_goals.push_back(g.waypoints[static_cast<std::size_t>(first)]);
    ring.groups.push_back(std::move(g));
  }
  return ring;
}

// Sums of the speed samples: along the corridor in each person's direction, and of |v|; and the
// closest approaches of the encounters.
struct RingSpeeds {
  double sum = 0.0;
  double sum2 = 0.0;
  double sum_abs = 0.0;
  std::int64_t n = 0;
  ClosestApproachStats approach;
};

// Adds every person's speed now to `speeds`.
void SampleSpeeds(const std::vector<int>& direction, const sim::Pedestrians& crowd,
                  const sim::PhysicsWorld& world, RingSpeeds* speeds) {
  for (std::size_t i = 0; i < crowd.status().size(); ++i) {
    const int id = crowd.status()[i].id;
    const Vec2 p = world.PedestrianPosition(id);
    const Vec2 v = world.PedestrianVelocity(id);
    const double pn = p.norm();
    if (pn < 1e-9) continue;
    const Vec2 tangent(-p.y() / pn, p.x() / pn);  // counter-clockwise
    const double along = direction[i] * v.dot(tangent);
    speeds->sum += along;
    speeds->sum2 += along * along;
    speeds->sum_abs += v.norm();
    ++speeds->n;
  }
}

// Walks the crowd through the warm-up and the measured duration, sampling every person's
// speed every sample_period after the warm-up, and following every encounter step by step.
RingSpeeds WalkAndMeasure(const FundamentalDiagramConfig& config, const std::vector<int>& direction,
                          sim::Pedestrians& crowd, sim::PhysicsWorld& world,
                          const RingObserver& observer) {
  const auto warmup_steps =
      static_cast<std::int64_t>(std::llround(config.warmup / config.time_step));
  const auto total_steps =
      warmup_steps + static_cast<std::int64_t>(std::llround(config.duration / config.time_step));
  const auto sample_every =
      std::max<std::int64_t>(1, std::llround(config.sample_period / config.time_step));
  RingSpeeds speeds;
  ClosestApproachTracker approach(crowd.status().size(), kEncounterRadius);
  std::vector<Vec2> positions(crowd.status().size());
  for (std::int64_t step = 0; step < total_steps; ++step) {
    crowd.Update(world);
    world.Step();
    if (step + 1 <= warmup_steps) continue;
    for (std::size_t i = 0; i < positions.size(); ++i)
      positions[i] = world.PedestrianPosition(crowd.status()[i].id);
    approach.Update(positions);
    if ((step + 1 - warmup_steps) % sample_every != 0) continue;
    approach.OpenEncounters(positions);
    SampleSpeeds(direction, crowd, world, &speeds);
    if (observer) observer(crowd, world, direction);
  }
  speeds.approach = approach.Finish();
  return speeds;
}

// The row's mean speed, its spread, the mean |v| and the deviation from Weidmann's curve.
void SetSpeedStatistics(const RingSpeeds& speeds, FundamentalDiagramRow* row) {
  const std::int64_t n = speeds.n;
  row->samples = n;
  if (n > 0) {
    row->mean_speed = speeds.sum / n;
    row->speed_std = std::sqrt(std::max(0.0, speeds.sum2 / n - row->mean_speed * row->mean_speed));
    row->mean_abs_speed = speeds.sum_abs / n;
  }
  row->encounters = speeds.approach.encounters;
  row->closest_approach = speeds.approach.mean;
  row->closest_approach_p05 = speeds.approach.p05;
  row->relative_deviation = row->weidmann_speed > 0.0
                                ? (row->mean_speed - row->weidmann_speed) / row->weidmann_speed
                                : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

double ClockwiseFraction(CrowdFlow flow) { return flow == CrowdFlow::kTwoWay ? 0.5 : 0.0; }

double WeidmannSpeed(double density, const WeidmannCurve& curve) {
  if (!(density > 0.0) || !std::isfinite(density)) {
    throw core::ConfigError(
        "density", "must be a number > 0 (persons/m²), got " + core::FormatNumber(density));
  }
  if (density >= curve.max_density) return 0.0;
  return curve.free_speed *
         (1.0 - std::exp(-curve.gamma * (1.0 / density - 1.0 / curve.max_density)));
}

sim::CrowdConfig DefaultCheckCrowd() {
  sim::CrowdConfig c;
  c.goal_tolerance = 2.0;
  c.loop_spread = 0.0;
  c.spawn_gap = 0.05;
  c.planner.cell_size = 0.05;
  c.planner.margin = 0.05;
  // Model `ttc`: people walk anywhere across the corridor, keeping their distance from the wall
  // rather than a lane of their own (the lanes are only where their loops' waypoints lie).
  c.lanes.tolerance = 3.5;
  return c;
}

FundamentalDiagramConfig::FundamentalDiagramConfig() : crowd(DefaultCheckCrowd()) {}

double FundamentalDiagramConfig::area() const {
  return core::kPi * (outer_radius() * outer_radius() - inner_radius * inner_radius);
}

void FundamentalDiagramConfig::Validate() const {
  core::RequirePositive("inner_radius", inner_radius);
  core::RequirePositive("width", width);
  core::RequireIntInRange("wall_segments", wall_segments, 16, 4096);
  core::RequireIntInRange("waypoints", waypoints, 6, 1000);
  core::RequirePositive("pedestrian_radius", pedestrian_radius);
  if (!(2.0 * (pedestrian_radius + crowd.planner.margin) < width)) {
    throw core::ConfigError("width", "must exceed twice pedestrian_radius + crowd.planner.margin");
  }
  core::RequirePositive("speed_mean", speed_mean);
  core::RequireNonNegative("speed_std", speed_std);
  core::RequireNonNegative("warmup", warmup);
  core::RequirePositive("duration", duration);
  core::RequirePositive("sample_period", sample_period);
  core::RequireInRange("time_step", time_step, 1e-4, 0.1);
  try {
    crowd.Validate();
  } catch (const core::ConfigError& e) {
    throw core::ConfigError("crowd." + e.key_path(), e.detail());
  }
}

FundamentalDiagramConfig ReadFundamentalDiagramConfig(const std::vector<std::string>& overrides) {
  if (overrides.empty()) {
    FundamentalDiagramConfig c;
    c.Validate();
    return c;
  }
  std::vector<io::ConfigOverride> parsed;
  for (const std::string& s : overrides) {
    io::ConfigOverride o = io::ParseOverride(s);
    // The scenarios' key for the crowd, so that a value tried here can be copied there.
    if (o.key_path.rfind("sim.crowd.", 0) == 0) o.key_path = o.key_path.substr(4);
    parsed.push_back(std::move(o));
  }
  YAML::Node root(YAML::NodeType::Map);
  io::ApplyOverrides(root, parsed);
  auto c = io::ReadConfig<FundamentalDiagramConfig>(root, "--set", parsed);
  c.Validate();
  return c;
}

void ValidateDensities(const std::vector<double>& densities) {
  if (densities.empty()) throw core::ConfigError("densities", "needs at least one density");
  const WeidmannCurve curve;
  for (double d : densities) {
    if (!(d > 0.0) || !std::isfinite(d) || d >= curve.max_density) {
      throw core::ConfigError("densities", "every density must be > 0 and < " +
                                               core::FormatNumber(curve.max_density) +
                                               " persons/m², got " + core::FormatNumber(d));
    }
  }
}

FundamentalDiagramRow RunDensity(const FundamentalDiagramConfig& config, CrowdFlow flow,
                                 double density, std::uint64_t seed, std::size_t index,
                                 const RingObserver& observer) {
  FundamentalDiagramRow row = RowForDensity(config, density);
  row.flow = flow;
  const core::Rng rng = core::Rng(seed).Split("fundamental_diagram").Split(index);
  core::Rng layout = rng.Split("layout");
  const LaneBand lanes = LaneBandOf(config);
  const Lattice lattice = RingLattice(row.count, lanes.min + kMaxJitter, lanes.max - kMaxJitter,
                                      layout.Uniform(0.0, 2.0 * core::kPi));
  row.lattice_spacing = lattice.spacing;
  const double needed = 2.0 * config.pedestrian_radius + config.crowd.spawn_gap;
  if (!(lattice.spacing >= needed + 1e-9)) {
    row.note = core::Printf(
        "%d pedestrians of radius %.2f m do not fit between the walls: the start lattice's "
        "spacing %.3f m is below 2 x radius + spawn gap = %.3f m",
        row.count, config.pedestrian_radius, lattice.spacing, needed);
    return row;
  }
  // Each start point is drawn from a small box round its site (by the crowd's own rng), small
  // enough that two boxes never hold points closer than `needed`.
  const double jitter =
      std::clamp(0.5 * (lattice.spacing - needed) / std::sqrt(2.0), 1e-3, kMaxJitter);
  const std::vector<int> direction =
      RandomDirections(lattice.sites.size(), ClockwiseFraction(flow), layout);
  const core::Rng crowd_rng = rng.Split("pedestrians");
  const RingGroups ring = RingWalkers(config, lattice, direction, jitter, lanes, layout, crowd_rng);

  const sim::StaticGeometry geometry = RingGeometry(config);
  sim::PhysicsConfig physics_config;
  physics_config.time_step = config.time_step;
  sim::PhysicsWorld world(geometry, physics_config);
  sim::Pedestrians crowd(ring.groups, config.crowd, geometry, crowd_rng, {}, world);
  for (std::size_t i = 0; i < ring.first_goals.size(); ++i) {
    if ((crowd.status()[i].goal - ring.first_goals[i]).norm() > 1e-9) ++row.misaligned_starts;
  }
  const RingSpeeds speeds = WalkAndMeasure(config, direction, crowd, world, observer);
  for (const sim::PedestrianStatus& st : crowd.status()) {
    row.yields += st.replans;
    row.goals_abandoned += st.goals_abandoned;
  }
  row.spawned = true;
  SetSpeedStatistics(speeds, &row);
  return row;
}

FundamentalDiagramResult SummarizeDiagram(CrowdFlow flow, std::vector<FundamentalDiagramRow> rows,
                                          double tolerance) {
  FundamentalDiagramResult out;
  out.flow = flow;
  out.rows = std::move(rows);
  out.tolerance = tolerance;
  double sq = 0.0;
  int spawned = 0;
  for (const FundamentalDiagramRow& row : out.rows) {
    if (!row.spawned) continue;
    ++spawned;
    const double d = row.mean_speed - row.weidmann_speed;
    sq += d * d;
    const double dev = std::abs(row.relative_deviation);
    out.max_abs_deviation = std::max(out.max_abs_deviation, dev);
    if (dev <= tolerance) ++out.rows_within;
  }
  out.rms_deviation =
      spawned > 0 ? std::sqrt(sq / spawned) : std::numeric_limits<double>::quiet_NaN();
  if (spawned == 0) out.max_abs_deviation = std::numeric_limits<double>::quiet_NaN();
  out.pass = !out.rows.empty() && out.rows_within == static_cast<int>(out.rows.size());
  return out;
}

FundamentalDiagramResult RunFundamentalDiagram(
    const FundamentalDiagramConfig& config, CrowdFlow flow, const std::vector<double>& densities,
    std::uint64_t seed, const std::function<void(const FundamentalDiagramRow&)>& on_row) {
  config.Validate();
  ValidateDensities(densities);
  std::vector<FundamentalDiagramRow> rows;
  for (std::size_t i = 0; i < densities.size(); ++i) {
    rows.push_back(RunDensity(config, flow, densities[i], seed, i));
    if (on_row) on_row(rows.back());
  }
  return SummarizeDiagram(flow, std::move(rows));
}

}  // namespace retrace::bench
