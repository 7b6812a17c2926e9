#pragma once
// The crowd checked against measurements: the fundamental diagram (walking speed against
// density) of the simulated crowd in a closed corridor, one-way and two-way, compared with
// Weidmann's (1993) empirical curve (docs/CROWD.md, "Crowd check").
//
// The corridor is a ring without ends, so the density stays constant: a solid inner disc and an
// outer wall of many thick segments. In one-way flow everyone walks counter-clockwise; in two-way
// flow half of them walk clockwise. Each walks along a loop of waypoints on a lane (radius) of its
// own, drawn at random. They start on a staggered lattice (random spawning jams long before the
// densest cases), warm up, and are then sampled: the speed along the corridor (the velocity's
// component along the ring's tangent in the person's walking direction), averaged over pedestrians
// and samples, and how close people come to each other (closest_approach.hpp). Nothing here
// prints.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "sim/pedestrians.hpp"
#include "sim/physics_world.hpp"

namespace retrace::bench {

/// The stream round the ring: everyone one way, or half each way.
enum class CrowdFlow { kOneWay, kTwoWay };

}  // namespace retrace::bench

template <>
struct retrace::core::EnumTraits<retrace::bench::CrowdFlow> {
  static constexpr std::array<std::pair<retrace::bench::CrowdFlow, std::string_view>, 2> kNames{
      {{retrace::bench::CrowdFlow::kOneWay, "one_way"},
       {retrace::bench::CrowdFlow::kTwoWay, "two_way"}}};
};

namespace retrace::bench {

/// Share of the people walking clockwise (the rest counter-clockwise): 0 in one-way flow, 0.5 in
/// two-way flow.
double ClockwiseFraction(CrowdFlow flow);

/// Weidmann's speed-density relation v(rho) = v0 (1 - exp(-gamma (1/rho - 1/rho_max))).
struct WeidmannCurve {
  double free_speed = 1.34;  ///< v0 (m/s)
  double gamma = 1.913;      ///< 1/m²
  double max_density = 5.4;  ///< rho_max (1/m²): the speed is 0 from here on
};

/// Walking speed (m/s) at `density` (persons/m², > 0) by Weidmann's curve; 0 at or above
/// max_density. Throws core::ConfigError("density") for a density that is not > 0 and finite.
double WeidmannSpeed(double density, const WeidmannCurve& curve = {});

/// The experiment: ring, bodies, timing and the crowd's behaviour. `--set` keys address it
/// (`ring.width=3`, `crowd.social_force.relaxation_time=0.4`; `sim.crowd.` is read as `crowd.`).
struct FundamentalDiagramConfig {
  double inner_radius = 3.5;  ///< m, radius of the solid inner disc
  double width = 3.5;         ///< m, corridor width between the disc and the outer wall
  int wall_segments = 96;     ///< segments of the outer wall (a circumscribed polygon)
  int waypoints = 24;         ///< loop waypoints per lane round the ring
  /// Body radius (m): shoulder width about 0.45 m, not the worlds' 0.3 m discs, with which a
  /// hexagonal packing caps the density at 3.2 /m².
  double pedestrian_radius = 0.2;
  double speed_mean = 1.34;    ///< desired speed (m/s), Weidmann's v0 (drawn per person)
  double speed_std = 0.26;     ///< m/s
  double warmup = 20.0;        ///< s before the measurement starts
  double duration = 40.0;      ///< s of measurement
  double sample_period = 0.2;  ///< s between speed samples
  double time_step = 0.01;     ///< s, the physics step
  /// The crowd's behaviour: the simulator's defaults except what the ring needs (see
  /// DefaultCheckCrowd()).
  sim::CrowdConfig crowd;

  FundamentalDiagramConfig();

  template <class V>
  void Reflect(V& v) {
    v("inner_radius", inner_radius);
    v("width", width);
    v("wall_segments", wall_segments);
    v("waypoints", waypoints);
    v("pedestrian_radius", pedestrian_radius);
    v("speed_mean", speed_mean);
    v("speed_std", speed_std);
    v("warmup", warmup);
    v("duration", duration);
    v("sample_period", sample_period);
    v("time_step", time_step);
    v("crowd", crowd);
  }
  /// Throws core::ConfigError naming the key.
  void Validate() const;

  double outer_radius() const { return inner_radius + width; }
  /// Walkable area (m²) of the ring: pi (R_out² - R_in²).
  double area() const;
};

/// The simulator's crowd defaults with the few changes the ring needs: a goal tolerance of
/// 2 m (each person aims at a waypoint of its own lane 2 to 3.8 m ahead, so that being pushed
/// aside does not make it turn back to a waypoint it missed), no loop spread (lanes are given),
/// a spawn gap of 5 cm and a walk-planner grid of 5 cm with a 5 cm margin (the lattice of the
/// densest cases must fit between the walls).
sim::CrowdConfig DefaultCheckCrowd();

/// The config from the defaults and `--set` overrides ("key.path=value"). Throws
/// core::ConfigError on an unknown key or an invalid value.
FundamentalDiagramConfig ReadFundamentalDiagramConfig(const std::vector<std::string>& overrides);

/// Centre distance (m) within which two people are in an encounter (ClosestApproachTracker).
inline constexpr double kEncounterRadius = 2.0;

/// The result at one density.
struct FundamentalDiagramRow {
  CrowdFlow flow = CrowdFlow::kTwoWay;
  double requested_density = 0.0;   ///< persons/m² asked for
  int count = 0;                    ///< pedestrians: round(requested density x area)
  double density = 0.0;             ///< count / area (persons/m²)
  bool spawned = false;             ///< false: the lattice does not fit (see note)
  std::string note;                 ///< why it was not spawned
  double mean_speed = 0.0;          ///< m/s along the corridor, over pedestrians and samples
  double speed_std = 0.0;           ///< m/s, standard deviation of the same samples
  double mean_abs_speed = 0.0;      ///< m/s, mean of |v|
  double weidmann_speed = 0.0;      ///< m/s at `density`
  double relative_deviation = 0.0;  ///< (mean_speed - weidmann_speed) / weidmann_speed
  std::int64_t samples = 0;
  double lattice_spacing = 0.0;  ///< m, closest distance between two start points
  /// Pedestrians whose first waypoint was not the one ahead (they walk round first).
  int misaligned_starts = 0;
  /// Times someone stepped aside after making no progress, and goals given up (whole run).
  int yields = 0;
  int goals_abandoned = 0;
  /// Encounters (centres within kEncounterRadius) during the measurement, and the mean and 5th
  /// percentile of their closest approaches (m between centres; NaN without encounters).
  std::int64_t encounters = 0;
  double closest_approach = 0.0;
  double closest_approach_p05 = 0.0;
};

/// Relative deviation from Weidmann's speed allowed at every density.
inline constexpr double kDiagramTolerance = 0.10;

struct FundamentalDiagramResult {
  CrowdFlow flow = CrowdFlow::kTwoWay;
  std::vector<FundamentalDiagramRow> rows;  ///< in the order asked for
  double rms_deviation = 0.0;      ///< m/s, RMS of mean_speed - weidmann_speed over spawned rows
  double max_abs_deviation = 0.0;  ///< largest |relative deviation| of a spawned row
  int rows_within = 0;             ///< spawned rows within the tolerance
  bool pass = false;               ///< every row spawned and within the tolerance
  double tolerance = kDiagramTolerance;
};

/// Checks a density list: non-empty, every value > 0 and finite and below Weidmann's
/// max_density. Throws core::ConfigError("densities").
void ValidateDensities(const std::vector<double>& densities);

/// Called at every speed sample of RunDensity with the crowd, the world and the walking direction
/// of each person (+1 counter-clockwise, -1 clockwise): a look at the ring while it runs.
using RingObserver =
    std::function<void(const sim::Pedestrians& crowd, const sim::PhysicsWorld& world,
                       const std::vector<int>& direction)>;

/// Builds the ring at one density, spawns, warms up and measures `flow`; `seed` and the row's
/// index decide every random draw (the two flows share the lattice, the lanes and the desired
/// speeds; only the directions differ). A density whose lattice does not fit gives a row with
/// spawned = false and a note, not an exception.
FundamentalDiagramRow RunDensity(const FundamentalDiagramConfig& config, CrowdFlow flow,
                                 double density, std::uint64_t seed, std::size_t index,
                                 const RingObserver& observer = {});

/// Every density in turn (`on_row` is called after each, e.g. for progress), then the summary.
/// Throws core::ConfigError on an invalid config or density list.
FundamentalDiagramResult RunFundamentalDiagram(
    const FundamentalDiagramConfig& config, CrowdFlow flow, const std::vector<double>& densities,
    std::uint64_t seed, const std::function<void(const FundamentalDiagramRow&)>& on_row = {});

/// The summary (RMS, largest deviation, pass) of one flow's rows; used by RunFundamentalDiagram.
FundamentalDiagramResult SummarizeDiagram(CrowdFlow flow, std::vector<FundamentalDiagramRow> rows,
                                          double tolerance = kDiagramTolerance);

}  // namespace retrace::bench
