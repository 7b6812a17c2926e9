#pragma once
// The procedurally generated campus shared by the likelihood and dynamic-rejection benchmarks:
// a 300 m x 300 m occupancy grid at 0.1 m (3000 x 3000 cells, lower-left corner at
// (-150, -150) m) of free ground with 70 building outlines, 120 walls and hedges and 3000
// trees, the same on every run (seeded).

#include <cstdint>
#include <vector>

#include "core/laser_scan.hpp"
#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "nav/grid_ray_caster.hpp"
#include "nav/likelihood_field.hpp"

namespace retrace::bench_micro {

inline constexpr int kCampusCells = 3000;         ///< cells along each side
inline constexpr double kCampusResolution = 0.1;  ///< m per cell

/// Builds the campus map (frame M); deterministic.
core::OccupancyGrid CampusMap();

/// Draws poses X_M (m, rad) uniformly from [-50, 50] m x [-50, 50] m x [-3, 3] rad with rng
/// until one lies more than 1.5 m from every obstacle of `field` (built on `map`), and returns it.
core::Pose2 FreeCampusPose(const core::OccupancyGrid& map, const nav::LikelihoodField& field,
                           core::Rng& rng);

/// A Hokuyo-like scan from X_M: 1081 beams over 270°, 0.05–30 m, cast in `caster`'s map, with
/// 2 cm of Gaussian range noise drawn from rng on every finite reading.
core::LaserScan CampusScan(const nav::GridRayCaster& caster, const core::Pose2& X_M,
                           core::Rng& rng);

/// A drive through the campus: from a free pose drawn with Rng(seed), keyframes 0.5 m apart,
/// turning `turn` rad per keyframe, straight on while there is room ahead (2 m), else turning on
/// the spot; a CampusScan at every keyframe.
struct CampusDrive {
  std::vector<core::Pose2> poses;
  std::vector<core::LaserScan> scans;
};
CampusDrive DriveThroughCampus(int keyframes, double turn, std::uint64_t seed);

}  // namespace retrace::bench_micro
