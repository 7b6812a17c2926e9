#pragma once
// The occupancy-grid mapper of the teaching run (paper §4.1): given the robot's pose in the
// map frame M (from odometry, eq. 2) and LiDAR scans, it integrates a scan at every keyframe
// by casting each beam through the grid cell by cell and applying the inverse sensor model in
// log-odds (eq. 3-4, nav/inverse_sensor_model.hpp). The grid grows as the robot travels.
// Keyframe poses make up the map's path.

#include <cstdint>
#include <vector>

#include "core/config.hpp"
#include "core/laser_scan.hpp"
#include "core/occupancy_grid.hpp"
#include "core/path.hpp"
#include "core/pose2.hpp"
#include "nav/inverse_sensor_model.hpp"
#include "nav/robot_geometry.hpp"

namespace retrace::nav {

/// Mapper parameters; defaults follow the original implementation where it had one.
struct MapperConfig {
  double resolution = 0.1;          ///< m per cell
  double initial_size = 20.0;       ///< m, side of the square grid centred on M's origin
  double keyframe_distance = 0.5;   ///< m travelled since the last keyframe
  double keyframe_angle_deg = 5.0;  ///< heading change since the last keyframe
  /// Clamp of every cell's log-odds. Wide, so that a wall seen head-on from many keyframes
  /// outlasts the few beams that graze its cells' free part, and a pedestrian crossing cells
  /// that are already saturated free during teaching leaves no trace.
  double log_odds_min = -8.0;
  double log_odds_max = 8.0;
  /// m: no-return (+inf) beams clear free cells up to this range or the scan's own range_max,
  /// whichever is shorter, without marking a hit, and never beyond a cell the map already holds
  /// as occupied (a dropout is not open space).
  double no_return_range = 10.0;
  InverseSensorModelConfig inverse_model;

  template <class V>
  void Reflect(V& v) {
    v("resolution", resolution);
    v("initial_size", initial_size);
    v("keyframe_distance", keyframe_distance);
    v("keyframe_angle_deg", keyframe_angle_deg);
    v("log_odds_min", log_odds_min);
    v("log_odds_max", log_odds_max);
    v("no_return_range", no_return_range);
    v("inverse_model", inverse_model);
  }
  /// Throws core::ConfigError naming the key path (e.g. "resolution",
  /// "inverse_model.sigma"): non-positive sizes or ranges, negative keyframe thresholds,
  /// log_odds_min >= 0 or log_odds_max <= 0.
  void Validate() const;
};

/// What the last integrated scan did, for diagnostics.
struct MapperStats {
  std::size_t keyframes = 0;      ///< scans integrated so far
  std::size_t beams_hit = 0;      ///< beams of the last keyframe that marked an end point
  std::size_t beams_cleared = 0;  ///< beams of the last keyframe that only cleared (no return)
  std::size_t beams_skipped = 0;  ///< invalid beams (NaN, -inf, below range_min) skipped
  std::size_t cells_updated = 0;  ///< distinct cells updated by the last keyframe
};

/// Builds one occupancy grid and its keyframe path in the frame M where it was started.
class Mapper {
 public:
  /// An empty map with the robot at the origin of M. Scans come from the LiDAR at
  /// robot.X_RL; finite readings beyond robot.range_max mark no hit (they only clear free
  /// space, like +inf). Throws core::ConfigError for an invalid config or geometry.
  Mapper(const MapperConfig& config, const RobotGeometry& robot);

  /// Sets the robot's current pose X_MR (m, rad, in M).
  void SetPose(const core::Pose2& X_MR) { X_MR_ = X_MR; }

  /// Integrates `scan` (taken at the current pose) if a keyframe is due: for the first scan,
  /// and once the robot has moved keyframe_distance or turned keyframe_angle_deg since the
  /// last keyframe. Records the pose in the path. Returns whether the scan was integrated.
  bool OnScan(const core::LaserScan& scan);

  /// Integrates `scan` taken from X_MR now, without keyframe gating and without recording a
  /// path pose. Each cell is updated at most once per scan: a cell holding a beam's end point
  /// takes the hit, any other cell the mean of the inverse-model values of the beams that
  /// meet it.
  void Integrate(const core::LaserScan& scan, const core::Pose2& X_MR);

  /// Whether OnScan would integrate a scan now (the first scan, or keyframe_distance moved or
  /// keyframe_angle_deg turned since the last keyframe).
  bool KeyframeDue() const;

  const core::OccupancyGrid& grid() const { return grid_; }
  /// Keyframe poses X_MR (in M), in the order they were taken.
  const core::Path& path() const { return path_; }
  /// The current pose X_MR (in M).
  const core::Pose2& pose() const { return X_MR_; }
  const MapperStats& stats() const { return stats_; }
  const MapperConfig& config() const { return config_; }

 private:
  static bool Marked(const std::vector<std::uint64_t>& bits, std::size_t cell);
  void ProposeNearEnd(std::size_t cell, float delta, bool end_cell);
  void ProposeFree(std::size_t cell);
  // Grows the grid to hold lo and hi (M) with a margin, and the scratch with it.
  void GrowFor(const core::Vec2& lo, const core::Vec2& hi);
  // Proposes the cells of a beam with a return at z (m) from p_ML along dir (M): free from
  // free_from up to `reach` (m) before the end point, then the inverse model's value (`hit` in
  // the end point's cell) up to `length` (m).
  void ProposeHitBeam(const core::Vec2& p_ML, const core::Vec2& dir, double z, double free_from,
                      double length, double reach, float hit);
  // Proposes as free the cells of a beam without a usable return from p_ML along dir (M), up to
  // clear_to (m) or the first blocking cell.
  void ProposeClearBeam(const core::Vec2& p_ML, const core::Vec2& dir, double length,
                        double clear_to);
  // Applies one update per touched cell (the hit, the mean near an end point, or the miss) and
  // clears the scratch bits.
  void ApplyProposals(float hit, float miss);

  MapperConfig config_;
  RobotGeometry robot_;
  core::OccupancyGrid grid_;
  core::Path path_;
  core::Pose2 X_MR_;
  MapperStats stats_;
  // Per-scan scratch. Most cells a scan touches are only passed through well before a beam's
  // end: for them one bit says so, in a bitmap small enough to stay in cache. Cells near end
  // points also get a proposal: the sum and number of those beams' log-odds updates and whether
  // a beam ended in the cell.
  struct Proposal {
    float sum = 0.0f;
    std::uint32_t count = 0;
    std::uint32_t end_cell = 0;
  };
  std::vector<Proposal> proposals_;          ///< one per cell, valid where near_bits_ is set
  std::vector<std::uint64_t> touched_bits_;  ///< one bit per cell: touched by this scan
  std::vector<std::uint64_t> near_bits_;     ///< one bit per cell: near an end point
  std::vector<std::size_t> touched_;         ///< the cells touched by this scan
};

}  // namespace retrace::nav
