#pragma once
// Incremental scan-to-map matching for the teaching drive (the paper's §5.4 remedy for maps
// blurred by odometry drift): each keyframe's scan is aligned with the partial map being built,
// starting from the odometry prediction. It is the real-time front end of scan-matching SLAM
// without a back end: no loop closure, no ground truth, so each partial map stays a map of its
// own, only less distorted.
//
// The matcher keeps the partial map's surface as points, not only as the occupancy grid: the
// end points of the keyframes matched so far, averaged per 5 cm voxel, in the map frame M. A
// 0.1 m grid would quantise every wall to its cell centres, and a fit against cell centres
// pulls the pose by up to half a cell towards them, differently for every set of walls in
// view (measured on the office floor: 3.4 cm of along-track error per 0.5 m keyframe, worse
// than odometry's 2.1 cm). Against the averaged points the fit is sub-centimetre.
//
// The fit is Gauss–Newton point-to-line ICP from the prediction: each end point is paired with
// its nearest map point within max_distance; its residual is the distance to the line through
// that point's neighbours (to the point itself where they do not form a line), Huber-weighted
// with scale σ. End points on geometry the map does not hold yet find no partner and do not
// pull. The Hessian H = Σ wᵢ Jᵢ Jᵢᵀ says how well the scan constrains the pose: for unit
// normals the smaller eigenvalue of its translation block is the number of end points that
// constrain the weakest direction. Below min_constraint (a featureless corridor along its
// axis, an open field), with too few paired end points or too few that fit, the match is
// refused and the caller keeps the odometry prediction.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/config.hpp"
#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "nav/robot_geometry.hpp"

namespace retrace::nav {

struct ScanMatcherConfig {
  double match_range = 30.0;  ///< m: end points farther from the LiDAR are not used
  double voxel_size = 0.05;   ///< m: map points are averaged per voxel of this side
  double point_spacing =
      0.1;  ///< m: a scan's end points closer than this to the previous kept one are dropped
  double max_distance = 0.3;  ///< m: farther from every map point, an end point is unpaired
  double sigma = 0.03;        ///< m: Huber scale of the residuals
  int max_iterations = 15;    ///< Gauss–Newton iterations
  int min_points = 15;        ///< paired end points needed to match at all
  /// Of the paired end points, the share whose residual must be within 3σ after the fit.
  double min_inlier_fraction = 0.5;
  double min_constraint = 12.0;  ///< smallest eigenvalue of H's translation block (≈ end points)
  double max_correction = 0.3;   ///< m: a fit that moves the pose farther is refused
  double max_correction_deg = 3.0;  ///< heading: a fit that turns the pose farther is refused

  template <class V>
  void Reflect(V& v) {
    v("match_range", match_range);
    v("voxel_size", voxel_size);
    v("point_spacing", point_spacing);
    v("max_distance", max_distance);
    v("sigma", sigma);
    v("max_iterations", max_iterations);
    v("min_points", min_points);
    v("min_inlier_fraction", min_inlier_fraction);
    v("min_constraint", min_constraint);
    v("max_correction", max_correction);
    v("max_correction_deg", max_correction_deg);
  }
  /// Throws core::ConfigError naming the key: match_range, voxel_size, max_distance, σ and the
  /// corrections > 0 (max_correction_deg <= 45), point_spacing >= 0, 1 <= max_iterations <=
  /// 100, min_points >= 3, 0 <= min_inlier_fraction <= 1, min_constraint >= 0.
  void Validate() const;
};

/// Why a match was refused (kMatched: it was not).
enum class MatchVerdict : std::uint8_t {
  kMatched,
  kEmptyMap,    ///< the map holds no points yet (its first keyframe)
  kFewPoints,   ///< fewer than min_points end points paired with map points
  kDegenerate,  ///< the scan does not constrain every direction (min_constraint)
  kPoorFit,     ///< too few end points fit, or the fit moved the pose too far
};

struct ScanMatch {
  core::Pose2 X_MR;  ///< the matched pose; the prediction when the match was refused
  MatchVerdict verdict = MatchVerdict::kEmptyMap;
  int points = 0;               ///< end points kept for matching
  int paired = 0;               ///< of those, paired with a map point at X_MR
  int inliers = 0;              ///< of those, with a residual within 3σ
  double min_constraint = 0.0;  ///< smallest eigenvalue of H's translation block
  double max_constraint = 0.0;  ///< largest eigenvalue of H's translation block

  bool accepted() const { return verdict == MatchVerdict::kMatched; }
};

/// Aligns scans with the points of one partial map. Not thread-safe; one per teach recorder.
class ScanMatcher {
 public:
  /// An empty map. Throws core::ConfigError for an invalid config or geometry.
  ScanMatcher(const ScanMatcherConfig& config, const RobotGeometry& robot);

  /// Aligns `scan`, taken by the robot at about X_MR_predicted (in M), with the map's points.
  /// Uses nothing but the map, the scan and the prediction.
  ScanMatch Match(const core::LaserScan& scan, const core::Pose2& X_MR_predicted);

  /// Adds the end points of `scan`, taken at X_MR, to the map (a keyframe, once its pose is
  /// final).
  void AddScan(const core::LaserScan& scan, const core::Pose2& X_MR);

  /// Forgets every point: the next partial map starts empty.
  void Clear();

  /// Map points (voxel means) held.
  std::size_t size() const { return voxels_.size(); }
  const ScanMatcherConfig& config() const { return config_; }

 private:
  struct Voxel {
    double sum_x = 0.0, sum_y = 0.0;
    int count = 0;
    core::Vec2 mean = core::Vec2::Zero();  ///< sum / count, kept up to date
  };
  // One end point's pairing: the line (or point) it is fitted to.
  struct Pairing {
    core::Vec2 q;       ///< the nearest map point
    core::Vec2 normal;  ///< unit normal of the local line; zero: fit to the point itself
  };

  void KeepPoints(const core::LaserScan& scan, std::vector<core::Vec2>* points_R) const;
  static std::uint64_t Key(int x, int y);
  bool Pair(const core::Vec2& p_M, Pairing* pairing) const;
  // The Gauss-Newton normal equations H delta = -b of one linearisation (robust weights), with
  // the number of paired end points and of inliers among them.
  struct NormalEquations {
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    int paired = 0;
    int inliers = 0;
  };
  // Whether the pairs must be found again at X: none yet, or an end point may have moved by
  // more than a tenth of a voxel since they were found at *paired_at.
  bool RepairDue(const core::Pose2& X, const std::optional<core::Pose2>& paired_at) const;
  // The normal equations of points_R_ at X, pairing them anew first when `repair`.
  void Linearize(const core::Pose2& X, bool repair, NormalEquations* eq);
  // The verdict on a fit ending at X (paired, inliers and constraints in `result`).
  MatchVerdict Judge(const ScanMatch& result, const core::Pose2& X,
                     const core::Pose2& X_MR_predicted) const;

  ScanMatcherConfig config_;
  RobotGeometry robot_;
  double search_cell_ = 0.0;  ///< side of the search cells (>= max_distance)
  std::vector<Voxel> voxels_;
  std::unordered_map<std::uint64_t, std::uint32_t> voxel_index_;  ///< fine key -> voxel
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>>
      search_cells_;                      ///< coarse key -> voxels
  std::vector<core::Vec2> points_R_;      ///< scratch: the scan being matched, robot frame
  std::vector<Pairing> pairings_;         ///< scratch: their pairs ...
  std::vector<std::uint8_t> paired_;      ///< ... where they have one
  mutable std::vector<core::Vec2> near_;  ///< scratch: candidate map points of one pairing
};

}  // namespace retrace::nav

template <>
struct retrace::core::EnumTraits<retrace::nav::MatchVerdict> {
  static constexpr std::array<std::pair<retrace::nav::MatchVerdict, std::string_view>, 5> kNames{
      {{retrace::nav::MatchVerdict::kMatched, "matched"},
       {retrace::nav::MatchVerdict::kEmptyMap, "empty_map"},
       {retrace::nav::MatchVerdict::kFewPoints, "few_points"},
       {retrace::nav::MatchVerdict::kDegenerate, "degenerate"},
       {retrace::nav::MatchVerdict::kPoorFit, "poor_fit"}}};
};
