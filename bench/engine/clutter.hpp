#pragma once
// Unmapped clutter (docs/METHOD.md, unmapped clutter): static objects (chairs, bins, parked
// bikes, boxes) and people standing still that are there during playback but were not while
// teaching, placed beside the route at a density per m² of a band either side of it, never in
// the robot's corridor along the route. Drawn deterministically from a core::Rng when the
// scenario loads; the scenario adds the objects to the playback world as playback-only objects
// and the people as pedestrian groups of mode `stand`.

#include <array>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "core/config.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "sim/pedestrian_config.hpp"
#include "sim/static_geometry.hpp"
#include "sim/world_file.hpp"

namespace retrace::bench {

/// What a clutter object is; each kind has one footprint (ClutterFootprint).
enum class ClutterKind : std::uint8_t { kChair, kBin, kBike, kBox };

}  // namespace retrace::bench

template <>
struct retrace::core::EnumTraits<retrace::bench::ClutterKind> {
  static constexpr std::array<std::pair<retrace::bench::ClutterKind, std::string_view>, 4> kNames{
      {{retrace::bench::ClutterKind::kChair, "chair"},
       {retrace::bench::ClutterKind::kBin, "bin"},
       {retrace::bench::ClutterKind::kBike, "bike"},
       {retrace::bench::ClutterKind::kBox, "box"}}};
};

namespace retrace::bench {

/// The scenario's `clutter` block. Off (no object, nothing drawn) while both densities are 0.
struct ClutterConfig {
  double density = 0.0;           ///< static objects per m² of the band
  double standing_density = 0.0;  ///< people standing still per m² of the band
  /// m from the route's centre line: objects' and people's centres lie within it.
  double band = 3.0;
  /// m kept free beyond sim.robot.radius either side of the route: the corridor no footprint
  /// enters is radius + clearance wide on each side.
  double clearance = 0.3;
  /// m of free space between a footprint and walls, buildings and other clutter.
  double gap = 0.1;
  /// What the objects are, drawn with equal probability.
  std::vector<ClutterKind> kinds = {ClutterKind::kChair, ClutterKind::kBin, ClutterKind::kBike,
                                    ClutterKind::kBox};
  /// m, a standing person's footprint.
  double person_radius = 0.25;

  template <class V>
  void Reflect(V& v) {
    v("density", density);
    v("standing_density", standing_density);
    v("band", band);
    v("clearance", clearance);
    v("gap", gap);
    v("kinds", kinds);
    v("person_radius", person_radius);
  }
  /// Throws core::ConfigError naming the key: densities in [0, 1] /m², band positive, clearance
  /// and gap non-negative, kinds not empty and without repeats, person_radius in [0.1, 0.5] m.
  void Validate() const;
  bool enabled() const { return density > 0.0 || standing_density > 0.0; }
};

/// A kind's footprint: a box (size, m) or, when size is zero, a circle of `radius` (m).
/// Rough sizes of common objects: chair 0.5 m square, bin 0.4 m across, bike 1.8 × 0.6 m,
/// box 0.6 m square.
struct ClutterFootprint {
  core::Vec2 size{0.0, 0.0};
  double radius = 0.0;
  /// m: the radius of the disc around the centre that holds the footprint at any yaw.
  double Bound() const { return radius > 0.0 ? radius : 0.5 * size.norm(); }
};
ClutterFootprint FootprintOf(ClutterKind kind);

/// The kinds' mean width (m) at a uniform yaw, averaged over `config.kinds`: perimeter / π for
/// each (Cauchy's formula for a convex footprint). Density × mean width is the clutter's
/// blocking rate: how often per metre a ray through the band meets an object.
double MeanClutterWidth(const ClutterConfig& config);

/// The blocking rate (1/m) of static unmapped clutter that `retrace calibrate-lidar` infers for
/// the Intel Research Lab log (docs/METHOD.md, "What the map does not hold": 0.041 objects per
/// m² of 0.60 m mean width), the one indoor log at hand. CalibratedClutterDensity converts it
/// to a scenario's kinds (the campus kinds: 0.030 per m²); scenarios stay without clutter unless
/// they ask for it.
inline constexpr double kCalibratedBlockingRate = 0.025;

/// kCalibratedBlockingRate / MeanClutterWidth(config): objects per m² of `config`'s kinds.
double CalibratedClutterDensity(const ClutterConfig& config);

/// Where the clutter may go: the route (W), the playback world's static geometry, the robot's
/// radius and a disc around the route's start kept free (so that the robot starts clear and
/// the crowd's keep-clear rule for its start holds).
struct ClutterSite {
  const std::vector<core::Vec2>* route = nullptr;
  const sim::StaticGeometry* geometry = nullptr;
  double robot_radius = 0.3;  ///< m
  double start_clear = 2.5;   ///< m around route.front()
};

/// The clutter drawn for one scenario.
struct Clutter {
  std::vector<sim::BoxConfig> boxes;       ///< chairs, bikes, boxes (W)
  std::vector<sim::CircleConfig> circles;  ///< bins (W)
  std::vector<core::Vec2> standing;        ///< where people stand (W)
  double band_area = 0.0;                  ///< m²: the free area of the band outside the corridor
};

/// Draws the clutter: round(density × band area) objects of uniformly drawn kinds, then
/// round(standing_density × band area) people, each at a uniform point of the band's free
/// area (0.2 m cells) with a uniform yaw, kept only if its footprint's bounding disc stays out
/// of the corridor, `gap` clear of the geometry and of the clutter placed before, and out of
/// the start disc (people: 0.5 m more from geometry, so the crowd's walk planner finds them a
/// free cell). Randomness: rng.Split("objects") and rng.Split("standing").
/// Throws core::ConfigError ("band" when the band holds no free area outside the corridor;
/// "density" / "standing_density" naming how many fit when 5000 draws in a row fail).
Clutter GenerateClutter(const ClutterConfig& config, const ClutterSite& site, const core::Rng& rng);

/// The standing people as pedestrian groups of mode `stand`, one per person, each spawning
/// within 1 cm of its spot.
std::vector<sim::PedestrianGroupConfig> StandingGroups(const Clutter& clutter,
                                                       double person_radius);

}  // namespace retrace::bench
