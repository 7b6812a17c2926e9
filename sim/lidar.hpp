#pragma once
// The simulated planar LiDAR (docs/DESIGN.md §4): exact closest hits over the static geometry (the
// world's, plus obstacles added at run time) and the pedestrians, Gaussian range noise, dropouts
// and spurious short returns, REP-117 readings.

#include <cstdint>
#include <span>
#include <vector>

#include "core/config.hpp"
#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "sim/ray_caster.hpp"
#include "sim/static_geometry.hpp"

namespace retrace::sim {

/// Range noise and spurious readings: per beam, the four-part mixture of Probabilistic Robotics
/// §6.3 (docs/METHOD.md, "The simulated LiDAR's mixture"). One uniform draw per beam picks a
/// dropout (dropout_probability), a short return (short_probability), a random return
/// (random_probability) or else the noisy true range. Defaults are those of a Hokuyo UTM-30LX:
/// the datasheet's accuracy is +-30 mm up to 10 m and +-50 mm up to 30 m, which sigma = 0.01 m +
/// 0.001 * range stays inside. With short_lambda and random_probability at 0 (their defaults)
/// no random number is drawn for them: scans are bit-identical to the three-part model's.
struct LidarNoiseConfig {
  double sigma0 = 0.01;               ///< m, standard deviation at range 0
  double sigma1 = 0.001;              ///< m per m of range: sigma = sigma0 + sigma1 * range
  double dropout_probability = 0.01;  ///< per beam: the beam reads +inf (no return; z_max)
  /// Per beam: a spurious return (ground, clutter) in [range_min, true range), or in
  /// [range_min, range_max) if nothing is in range, with the density of short_lambda.
  double short_probability = 0.002;
  /// 1/m: a short return's density is proportional to exp(-short_lambda * z) on its interval
  /// (a truncated exponential); 0 is uniform, the limit of small short_lambda.
  double short_lambda = 0.0;
  /// Per beam: a random return, uniform in [range_min, range_max), whatever the geometry.
  double random_probability = 0.0;

  template <class V>
  void Reflect(V& v) {
    v("sigma0", sigma0);
    v("sigma1", sigma1);
    v("dropout_probability", dropout_probability);
    v("short_probability", short_probability);
    v("short_lambda", short_lambda);
    v("random_probability", random_probability);
  }
  /// Throws core::ConfigError naming the key (e.g. "sigma0"); the three probabilities must not
  /// sum to more than 1 ("random_probability" named then).
  void Validate() const;
};

/// Sensor geometry, rate and mounting. Beam i points at -fov/2 + i * fov / (beams - 1) in L
/// (the fan is centred on L's x axis; with fov 360 the first and last beams coincide).
struct LidarConfig {
  double fov_deg = 270.0;
  int beams = 1081;
  double range_min = 0.05;  ///< m
  double range_max = 30.0;  ///< m
  double rate_hz = 20.0;
  core::Pose2 mount;  ///< X_RL: the LiDAR frame L in the robot frame R
  LidarNoiseConfig noise;

  template <class V>
  void Reflect(V& v) {
    v("fov_deg", fov_deg);
    v("beams", beams);
    v("range_min", range_min);
    v("range_max", range_max);
    v("rate_hz", rate_hz);
    v("mount", mount);
    v("noise", noise);
  }
  /// Throws core::ConfigError naming the key path (e.g. "beams", "noise.sigma0").
  void Validate() const;
};

/// What produced a beam's reading.
enum class BeamSource : std::uint8_t {
  kNothing,     ///< no surface within range_max: reads +inf
  kStatic,      ///< static geometry (a noisy range, or +-inf when out of the valid interval)
  kPedestrian,  ///< a pedestrian (likewise)
  kSpurious,    ///< a spurious return: short or random
  kDropout,     ///< the return was lost: reads +inf
};

/// Ground truth of one beam.
struct BeamTruth {
  BeamSource source = BeamSource::kNothing;
  /// Id of the pedestrian the beam truly meets first (-1 if none), whatever the reading's
  /// source: a dropout or spurious reading on a pedestrian beam keeps the id.
  int pedestrian_id = -1;
  /// Noise-free distance (m) from L to the first surface along the beam; +inf if none within
  /// range_max.
  double range = 0.0;
};

/// One scan and its per-beam ground truth (truth[i] belongs to scan.ranges[i]).
struct LidarReading {
  core::LaserScan scan;
  std::vector<BeamTruth> truth;
};

/// A 2D LiDAR in a static world, seeing pedestrians given per scan.
///
/// Readings follow REP-117: a beam whose true range exceeds range_max, and a dropout, read
/// +inf; a surface closer than range_min reads -inf ("too close"). Noise is added to the true
/// range; a noisy value above range_max reads +inf (the sensor reports nothing beyond its
/// maximum, never a clamped max), one below range_min reads -inf, so no reading is ever
/// negative, zero or outside [range_min, range_max] while finite.
class Lidar {
 public:
  /// Validates the config (throws core::ConfigError) and builds the ray caster over a copy of
  /// the geometry (no reference kept).
  Lidar(const LidarConfig& config, const StaticGeometry& geometry);

  /// One scan from the robot at X_WR (W), the LiDAR at X_WR * mount. Pedestrians are circles
  /// in W (finite centres, radius > 0, id >= 0: checked). stamp (s) is copied into the scan. All
  /// randomness is drawn from rng, so equal inputs and rng state give bit-identical readings.
  LidarReading Scan(const core::Pose2& X_WR, std::span<const DynamicCircle> pedestrians,
                    double stamp, core::Rng& rng) const;

  /// Adds the polygons and circles of `solids` (W, m; obstacles placed at run time) to what the
  /// LiDAR sees from the next scan on, as static geometry: BeamTruth source kStatic, and they
  /// win a tie with a pedestrian like walls do. Meant for a few solids (tens): each is tested
  /// exactly on the beams its bounding disc covers, outside the precomputed ray caster. Open
  /// edges (imported maps) are not supported (checked).
  void AddObstacles(const StaticGeometry& solids);
  /// Every solid added by AddObstacles so far.
  const StaticGeometry& obstacles() const { return obstacles_; }

  const LidarConfig& config() const { return config_; }
  const RayCaster& ray_caster() const { return caster_; }
  double angle_min() const { return angle_min_; }              ///< rad, in L
  double angle_increment() const { return angle_increment_; }  ///< rad

 private:
  LidarConfig config_;
  RayCaster caster_;
  double angle_min_ = 0.0;
  double angle_increment_ = 0.0;
  std::vector<Vec2> beam_dirs_L_;  // unit beam directions in L
  // Added obstacles: for the beam selection, each one's bounding disc and its own primitives.
  struct Obstacle {
    Circle bound{Vec2::Zero(), 0.0};   // W; contains the whole solid
    std::vector<Segment> edges;        // a polygon's edges; empty for a circle
    Circle circle{Vec2::Zero(), 0.0};  // the circle; radius 0 for a polygon
  };
  StaticGeometry obstacles_;
  std::vector<Obstacle> obstacle_parts_;

  struct ScanBeams;
  // The beams of a scan taken from X_WL (W).
  ScanBeams BeamsFrom(const core::Pose2& X_WL) const;
  // Per beam, the range of the nearest pedestrian that it meets within limit[k] (m, range_max
  // on entry) into limit[k], and that pedestrian's id into truth[k].pedestrian_id (-1 on entry).
  static void HitPedestrians(const ScanBeams& beams, std::span<const DynamicCircle> pedestrians,
                             std::span<double> limit, std::span<BeamTruth> truth);
  // Per beam, the range (m) of the nearest static geometry (added obstacles included) within
  // limit[k], or +inf.
  void CastStatic(const ScanBeams& beams, std::span<const double> limit,
                  std::span<double> wall) const;
};

}  // namespace retrace::sim
