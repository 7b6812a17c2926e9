#pragma once
// `retrace calibrate-lidar`: the beam model's intrinsic parameters fitted to a log's real scans
// against the map of the same place (docs/METHOD.md, "Calibrating the LiDAR from a log"). Each
// beam's expected range z* is ray-cast (nav/grid_ray_caster.hpp) in the map of a consistent
// teach folder from the log's reference pose at the scan's stamp, composed with the LiDAR mount;
// only beams whose z* the map knows are used: the ray reaches an occupied cell before
// range_max through known free cells only. The fit is nav::FitBeamMixture over the whole window
// and over each half of it by time.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/calibration/unmapped_calibration.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/replay/log_streams.hpp"
#include "bench/replay/log_teach.hpp"
#include "logs/sensor_log.hpp"
#include "nav/beam_mixture_fit.hpp"
#include "sim/lidar.hpp"

namespace retrace::bench {

struct LidarCalibrationOptions {
  /// Beams with a known expected range needed in each half of the window.
  std::size_t min_beams_per_half = 1000;
  nav::BeamFitOptions fit;
};

/// The beams of the window, sorted out: the samples with a known z*, in log order.
struct CalibrationBeams {
  std::vector<nav::BeamSample> samples;
  std::vector<double> times;  ///< one per sample: its scan's log time (s, as --from/--to)
  std::size_t scans = 0;      ///< scans with a reference pose
  std::size_t beams = 0;      ///< all beams of those scans
  std::size_t unknown = 0;    ///< z* not known to the map (open, unknown cells, off the map)
  std::size_t invalid = 0;    ///< known z* but the reading below range_min, -inf or NaN
  std::size_t scans_without_reference = 0;
  double first_s = 0.0;    ///< log time (s, as --from/--to) of the first scan used
  double last_s = 0.0;     ///< ... and of the last
  double range_min = 0.0;  ///< m, the log's LiDAR (its first scan)
  double range_max = 0.0;
  /// Every beam with a reading, walked through the map
  /// (bench/calibration/unmapped_calibration.hpp).
  std::vector<UnmappedBeam> unmapped;
};

/// One fit and the part of the window it covers.
struct LidarFit {
  nav::BeamFitResult result;
  double from_s = 0.0;  ///< log time (s, as --from/--to)
  double to_s = 0.0;
};

/// What the map does not hold, over one part of the window.
struct UnmappedPart {
  UnmappedFit fit;
  double from_s = 0.0;
  double to_s = 0.0;
};

struct LidarCalibration {
  CalibrationBeams beams;
  LidarFit whole, first_half, second_half;
  UnmappedPart unmapped_whole, unmapped_first_half, unmapped_second_half;
};

/// Refuses a teach folder whose map is not the world: `mode` must be consistent (from the folder's
/// name, `<mode>/teach`; partial, scan_matched and single maps are built from odometry), with
/// one map and a reference. Throws core::ConfigError("--teach", ...).
void RequireWorldMap(const ModeTeach& teach, const std::filesystem::path& teach_dir,
                     std::optional<MapMode> mode);

/// The beams of `index` in `window`, each with its expected range in the map of `world_teach`,
/// and walked through it for what the map does not hold (the band is `clutter`'s around the
/// window's reference). Throws core::IoError for a log without a reference.
CalibrationBeams CollectCalibrationBeams(const logs::LogIndex& index, const LogStreams& streams,
                                         const ModeTeach& world_teach, const LogWindow& window,
                                         const ClutterConfig& clutter);

/// Fits the whole window and its halves: the mixture, then what the map does not hold (a
/// reading is short when it ends before the map's range minus 3 σ_hit, less the hit offset, of
/// the whole window's mixture). Throws core::IoError when a half has fewer than
/// options.min_beams_per_half beams with a known expected range, core::ConfigError
/// ("--max-iterations") when a fit does not converge.
LidarCalibration FitLidarCalibration(CalibrationBeams beams, const std::string& log_name,
                                     const LidarCalibrationOptions& options,
                                     const ClutterConfig& clutter);

/// The simulated world that reproduces what the map does not hold (indirect inference):
/// FitUnmapped's estimates are not the parameters that produce them (the sensor's short and
/// random readings, rays that only clip unknown cells, an object's cells passed by grazing
/// rays), so the log is simulated with the fitted sensor, its scans estimated the same way,
/// and the unknown cells' free path and the clutter's density are each scaled by real /
/// simulated estimate until they agree within 5 % and 10 % (at most 8 simulations, one seed).
/// Readings that end in unknown cells needed in each half of the window to estimate their free
/// path; with fewer the unknown cells stay open.
inline constexpr std::size_t kMinUnknownHitsPerHalf = 100;

struct WorldInference {
  /// m, for sim.unknown_free_path; 0 (left open) with too few hits in unknown cells, or when
  /// rays cross them farther than the LiDAR's range_max.
  double free_path = 0.0;
  bool unknown_hits_enough = false;  ///< kMinUnknownHitsPerHalf in each half
  double density = 0.0;              ///< static objects per m², for clutter.density
  UnmappedFit simulated;             ///< the last simulation's whole fit
  int simulations = 0;
  bool converged = false;
};
/// The simulated sensor is WorldNoise. Throws core::ConfigError("clutter.kinds", ...) when the
/// clutter does not fit beside the route.
WorldInference InferSimulatedWorld(const logs::LogIndex& index, const LogStreams& streams,
                                   const ModeTeach& world_teach,
                                   const std::filesystem::path& world_teach_dir,
                                   const LogWindow& window, const LidarCalibration& calibration,
                                   const ClutterConfig& clutter);

/// The noise of a simulated world that holds what the map does not (unknown cells, clutter):
/// NoiseOfMixture without short returns, which the world's things now make; the mixture's
/// z_short, fitted on real scans, is mostly those things (on the campus drive with clutter,
/// 0.09), and drawing it too would cut the rays short twice.
sim::LidarNoiseConfig WorldNoise(const nav::BeamMixture& mixture);

/// The simulated LiDAR's noise that draws the fitted mixture: sigma0 = σ_hit, sigma1 = 0,
/// dropout_probability = z_max, short_probability = z_short, short_lambda = λ_short,
/// random_probability = z_rand (the hit part takes the rest, z_hit).
sim::LidarNoiseConfig NoiseOfMixture(const nav::BeamMixture& mixture);

}  // namespace retrace::bench
