#pragma once
// Plain data for the figures (core types and std only), filled by the harness from a results
// folder: maps with io::ReadRosMap, paths and trajectories with io::ReadTum (or the teach
// bundle's path files), switch poses from switch_poses.txt, metrics from metrics.json.
//
// Frames (docs/DESIGN.md §2): W the world (ground truth), M_k partial map k, O odometry. Every
// field says which frame it is in; figures never guess a transform the data does not give.

#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "viz/view.hpp"

namespace retrace::viz {

struct Circle {
  Vec2 center = Vec2::Zero();  ///< m
  double radius = 0.0;         ///< m
};

/// The world's static geometry in W, as the simulator holds it.
struct WorldShapes {
  std::vector<std::vector<Vec2>> polygons;      ///< filled solids (buildings, boxes, thick walls)
  std::vector<Circle> circles;                  ///< trees, poles
  std::vector<std::pair<Vec2, Vec2>> segments;  ///< thin edges (walls of imported maps)

  bool empty() const { return polygons.empty() && circles.empty() && segments.empty(); }
  /// The box around every shape (empty when there are none).
  Box2 Bounds() const;
};

/// One partial map with what was recorded in it.
struct PartialMapView {
  std::string label;              ///< panel title; empty: "map k"
  core::OccupancyGrid grid;       ///< in M_k
  core::Pose2 X_WM;               ///< where M_k sits in W (ground truth at the map's start)
  std::vector<core::Pose2> path;  ///< taught path (keyframes) X_{M_k R}
  core::Pose2 start;              ///< start of segment k in M_k (identity by design)
  std::optional<core::Pose2> switch_pose;  ///< X_{M_k S}; none for the last map
};

/// A trajectory with its legend label.
struct Trajectory {
  std::string label;
  std::vector<core::Pose2> poses;
};

/// maps.png (paper Fig. 1): the world with the whole route and switch points, then every
/// partial map in its own frame with its path, start and switch point.
/// What the teaching figure's route is, for its titles: a log's drive has no ground truth.
enum class RouteSource {
  kGroundTruth,  ///< the simulator's X_WR
  kReference,    ///< a log's reference trajectory X_WR
  kOdometry,     ///< a log without a reference: the odometry X_OR, in the odometry frame O
};

struct MapsFigureData {
  WorldShapes world;
  std::vector<core::Pose2> route;         ///< teaching ground truth X_WR (see route_source)
  std::vector<core::Pose2> switch_poses;  ///< ground truth X_WR where map k ended, k = 0, 1, ...
  std::vector<PartialMapView> maps;
  RouteSource route_source = RouteSource::kGroundTruth;
};

/// maps_compare.png (paper Fig. 6): maps of the same route side by side, each in its own
/// frame (typically the consistent map and the single odometry map; X_WM is not used).
struct MapsCompareFigureData {
  std::vector<PartialMapView> maps;
};

/// playback_<mode>.png (paper Fig. 7): the target path and every run's ground truth over the
/// world.
struct PlaybackFigureData {
  std::string mode;
  WorldShapes world;
  std::vector<core::Pose2> target;        ///< teaching ground truth X_WR (the taught path)
  std::vector<Trajectory> runs;           ///< ground truth X_WR of each playback run
  std::vector<core::Pose2> switch_poses;  ///< ground truth X_WR of the teaching's map switches
};

/// One drive seen by ground truth and by wheel odometry.
struct OdometryDrive {
  std::string label;                  ///< "teaching", "playback run 0"
  std::vector<core::Pose2> truth;     ///< X_WR
  std::vector<core::Pose2> odometry;  ///< X_OR; drawn in W after aligning its first pose with
                                      ///< the first ground-truth pose (X_WO = X_WR0 X_OR0^-1)
};

/// odometry.png (paper Fig. 8): one panel per drive (teaching and one playback run).
struct OdometryFigureData {
  WorldShapes world;
  std::vector<OdometryDrive> drives;
};

/// A measurement likelihood over (x, y) at a fixed heading.
struct LikelihoodGrid {
  int width = 0;
  int height = 0;
  double resolution = 0.05;    ///< m per cell
  Vec2 origin = Vec2::Zero();  ///< lower-left corner of cell (0, 0), frame of true_pose (m)
  std::vector<double> values;  ///< row-major, row 0 = lowest y; non-finite = no value
  bool log_values = true;      ///< values are log-likelihoods (else likelihoods >= 0)
};

/// likelihood.png (paper Fig. 5): the same moment without and with dynamic point rejection.
struct LikelihoodFigureData {
  LikelihoodGrid without_rejection;
  LikelihoodGrid with_rejection;
  core::Pose2 true_pose;            ///< the robot's true pose (map frame of the grids)
  std::vector<Circle> pedestrians;  ///< same frame
  double time_s = std::numeric_limits<double>::quiet_NaN();  ///< shown when finite
  /// false for a log: no pedestrians known, and the true pose is the log's reference
  bool simulated = true;
};

/// A LiDAR end point with what the localizer and the simulator know about it.
struct ScanPoint {
  Vec2 point = Vec2::Zero();     ///< m, map frame
  bool rejected = false;         ///< excluded by dynamic point rejection (eq. 7-9)
  bool hits_pedestrian = false;  ///< the simulator's truth: the beam hit a pedestrian
};

/// snapshot.png (paper Fig. 4): one localization moment in the frame of map `map_index`.
struct SnapshotData {
  double time_s = 0.0;
  int map_index = 0;
  core::OccupancyGrid grid;            ///< the map, M
  std::vector<core::Pose2> path;       ///< taught path in M (optional)
  std::vector<core::Pose2> particles;  ///< X_MR per particle
  std::vector<double> weights;         ///< one per particle (any scale); empty: equal
  core::Pose2 estimate;                ///< X_MR
  core::Pose2 truth;                   ///< local ground truth X_MR
  std::vector<ScanPoint> scan;         ///< end points in M
  std::vector<Circle> pedestrians;     ///< in M
  double robot_radius = 0.0;           ///< m, the robot's (the run's sim.robot.radius)
  /// false for a log: which beams hit people is unknown, and the truth is the log's reference
  bool simulated = true;
};

/// Errors of one run along the route.
struct ErrorSeries {
  std::string label;
  std::vector<double> arc_length;          ///< m along the taught path, one per sample
  std::vector<double> tracking_error;      ///< m; NaN: none
  std::vector<double> localization_error;  ///< m; NaN: none
};

/// errors.png: tracking and localization error along the route, map switches marked.
struct ErrorsFigureData {
  std::string mode;
  std::vector<ErrorSeries> runs;
  std::vector<double> switch_arc_lengths;  ///< m along the taught path
  /// What the horizontal axis and the top panel show; a log's run has no controller of its own,
  /// so its top panel is how far its driver stayed from the taught path.
  std::string x_label = "arc length along the taught path (m)";
  std::string top_title = "Tracking error: distance to the taught path";
  std::string top_y_label = "tracking error (m)";
};

/// One metric of one mode: a value and an optional interval (a CI, min-max, ...).
struct MetricValue {
  std::string metric;  ///< display name with unit, e.g. "tracking error mean (m)"
  double value = std::numeric_limits<double>::quiet_NaN();
  double lower = std::numeric_limits<double>::quiet_NaN();  ///< error bar; NaN: none
  double upper = std::numeric_limits<double>::quiet_NaN();
};

struct ModeMetrics {
  std::string mode;  ///< "partial", "single", "consistent", ...
  std::vector<MetricValue> metrics;
};

/// comparison.png: the modes' metrics side by side, one bar group per metric.
struct ComparisonFigureData {
  std::string scenario;
  std::vector<ModeMetrics> modes;
  std::string note;  ///< what the numbers are (runs, pooling); shown under the title
};

/// A quick look at a world file (`retrace world`): geometry, route, pedestrians, robot.
struct WorldFigureData {
  std::string name;
  WorldShapes world;
  std::vector<Vec2> route;          ///< W
  std::vector<Circle> pedestrians;  ///< W
  std::optional<core::Pose2> robot;
  double robot_radius = 0.0;  ///< m, the robot's
};

}  // namespace retrace::viz
