#pragma once
// A localization moment worth a figure (paper Fig. 4 and 5): the measurement update of a run in
// which the most tested beams hit pedestrians. It keeps the particles, the scan with each
// beam's use (weighted / rejected as dynamic / not tested) and the LiDAR's own label, and the
// measurement likelihood over (x, y) around the true pose with and without the rejection.

#include <cstdint>
#include <vector>

#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "sim/static_geometry.hpp"

namespace retrace::bench {

/// The summed beam log-likelihood of the likelihood field on a grid of positions in M (the
/// heading fixed at the true one), once with every tested beam and once without the beams the
/// dynamic-point test rejected.
struct LikelihoodSlice {
  core::Vec2 origin{0.0, 0.0};      ///< M, centre of cell (0, 0)
  double resolution = 0.05;         ///< m
  int size = 0;                     ///< cells per side (odd: the true pose is the centre cell)
  double theta = 0.0;               ///< heading of every grid pose (rad, M)
  std::vector<float> all_beams;     ///< row-major, y up
  std::vector<float> static_beams;  ///< the same without the rejected beams
};

struct LocalizationSnapshot {
  double time = 0.0;
  int map_index = 0;
  int pedestrian_beams = 0;  ///< tested beams that hit a pedestrian (what picked this moment)
  core::Pose2 X_WR;          ///< ground truth in W
  core::Pose2 X_MR_truth;    ///< local ground truth in the map
  core::Pose2 X_MR_estimate;
  core::Pose2 X_RL;                    ///< LiDAR mount
  std::vector<core::Pose2> particles;  ///< X_MR of each particle after the update
  std::vector<double> weights;
  core::LaserScan scan;
  std::vector<std::uint8_t> beam_use;  ///< nav::BeamUse per beam (0 unused, 1 used, 2 rejected)
  /// 1 where the beam hit a pedestrian (simulator truth); empty: unknown (a log)
  std::vector<std::uint8_t> pedestrian;
  std::vector<sim::DynamicCircle> pedestrians_W;  ///< where the pedestrians were (W)
  LikelihoodSlice likelihood;
};

}  // namespace retrace::bench
