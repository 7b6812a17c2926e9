#include "bench/calibration/lidar_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>

#include "bench/calibration/log_simulate.hpp"
#include "core/errors.hpp"
#include "io/ros_map.hpp"
#include "nav/grid_ray_caster.hpp"
#include "nav/likelihood_field.hpp"

namespace retrace::bench {

namespace {

// The map with every cell that is neither occupied nor known free made occupied: a ray cast in
// it stops at the first unknown cell as well.
core::OccupancyGrid UnknownAsOccupied(const core::OccupancyGrid& grid, double occupied_threshold) {
  core::OccupancyGrid blocked = grid;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const double p = grid.Probability({x, y});
      if (p >= io::kRosMapKnownFreeBelow && p < occupied_threshold)
        blocked.SetProbability({x, y}, io::kRosMapOccupiedProbability);
    }
  }
  return blocked;
}

// Expected ranges where the map knows them: the range to the first occupied cell when the cast
// in the map with unknown cells made occupied stops at the same range.
class KnownRangeCaster {
 public:
  KnownRangeCaster(const core::OccupancyGrid& grid, double range_max)
      : map_(grid, {}, range_max),
        blocked_(UnknownAsOccupied(grid, nav::LikelihoodFieldConfig{}.occupied_threshold), {},
                 range_max),
        map_caster_(map_),
        blocked_caster_(blocked_),
        range_max_(range_max) {}

  struct Ranges {
    double map = 0.0;    ///< m, the first occupied cell (unknown cells open); range_max if none
    double known = 0.0;  ///< m, z* where the map knows it, NaN where not
  };
  Ranges Cast(const core::Vec2& origin, const core::Vec2& dir) const {
    const double z = map_caster_.Cast(origin, dir, range_max_);
    if (z == nav::kNoHit) return {range_max_, std::nan("")};
    return {z, blocked_caster_.Cast(origin, dir, range_max_) == z ? z : std::nan("")};
  }

 private:
  nav::LikelihoodField map_, blocked_;
  nav::GridRayCaster map_caster_, blocked_caster_;
  double range_max_;
};

// The beams of one scan from the LiDAR pose X_ML into *beams.
void AddScanBeams(const core::LaserScan& scan, double log_time_s, const core::Pose2& X_ML,
                  const KnownRangeCaster& caster, const UnmappedMap& unmapped,
                  BandObservations* observations, CalibrationBeams* beams) {
  const core::Vec2 origin = X_ML.translation();
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    ++beams->beams;
    const double a = X_ML.theta + scan.Angle(i);
    const core::Vec2 dir(std::cos(a), std::sin(a));
    const KnownRangeCaster::Ranges cast = caster.Cast(origin, dir);
    const double r = scan.ranges[i];
    const bool valid = r >= beams->range_min;
    const double z = r >= beams->range_max ? std::numeric_limits<double>::infinity() : r;
    if (valid) {
      beams->unmapped.push_back(unmapped.Walk(log_time_s, origin, dir, z, cast.map, observations));
    }
    const double z_star = cast.known;
    if (!(z_star > beams->range_min)) {  // NaN: unknown
      ++beams->unknown;
      continue;
    }
    if (!valid) {
      ++beams->invalid;
      continue;
    }
    beams->samples.push_back({z, z_star});
    beams->times.push_back(log_time_s);
  }
}

std::string Count(std::size_t n) { return std::to_string(n); }

// The fit of the samples in [lo, hi) of `beams`, refused below `min_beams` or unconverged.
LidarFit FitPart(const CalibrationBeams& beams, std::size_t lo, std::size_t hi,
                 const std::string& what, const std::string& log_name,
                 const LidarCalibrationOptions& options, std::size_t min_beams) {
  min_beams = std::max<std::size_t>(min_beams, 1);
  if (hi - lo < min_beams) {
    throw core::IoError(
        log_name + ": only " + Count(hi - lo) + " beams in the " + what + " (of " +
        Count(beams.beams) + " in " + Count(beams.scans) +
        " scans) have an expected range that the map knows; at least " + Count(min_beams) +
        " are needed: the map does not cover this part of the log (" + Count(beams.unknown) +
        " beams meet unknown cells, leave the map or meet nothing within range_max)");
  }
  const std::span<const nav::BeamSample> part(beams.samples.data() + lo, hi - lo);
  LidarFit fit{nav::FitBeamMixture(part, beams.range_min, beams.range_max, options.fit),
               beams.times[lo], beams.times[hi - 1]};
  if (!fit.result.converged) {
    throw core::ConfigError(
        "--max-iterations",
        "the EM fit of the " + what + " did not converge in " +
            Count(static_cast<std::size_t>(fit.result.iterations)) + " iterations (last change " +
            core::FormatNumber(fit.result.last_change) + ", tolerance " +
            core::FormatNumber(options.fit.tolerance) +
            "); allow more iterations, or check that the map is the log's place");
  }
  return fit;
}

}  // namespace

void RequireWorldMap(const ModeTeach& teach, const std::filesystem::path& teach_dir,
                     std::optional<MapMode> mode) {
  if (mode != MapMode::kConsistent) {
    throw core::ConfigError(
        "--teach", teach_dir.string() + " is " +
                       (mode ? "a " + std::string(core::EnumName(*mode)) + " teach folder"
                             : "not a <mode>/teach folder") +
                       ": calibration needs a map that is the world, a consistent teach folder "
                       "built from the reference (log-teach's consistent/teach)");
  }
  if (teach.bundle.maps.size() != 1 || teach.trace.X_WR.empty()) {
    throw core::ConfigError("--teach", teach_dir.string() + " holds " +
                                           Count(teach.bundle.maps.size()) + " maps" +
                                           (teach.trace.X_WR.empty() ? " and no reference" : "") +
                                           ": a consistent teach folder holds one map and its "
                                           "reference (gt.tum)");
  }
}

namespace {

// The walk's map for a window: the map's cells sorted out around the window's reference.
UnmappedMap WindowUnmappedMap(const logs::LogIndex& index, const LogStreams& streams,
                              const ModeTeach& world_teach, const LogWindow& window,
                              const ClutterConfig& clutter) {
  const TeachMapTrace& trace = world_teach.trace.maps.front();
  const core::Pose2 X_MW = trace.X_MR.front() * trace.X_WR.front().Inverse();
  const double origin_s = 1e-9 * static_cast<double>(index.origin_ns);
  const std::vector<core::Vec2> route =
      RouteInMap(streams.reference, X_MW, origin_s + window.from_s, origin_s + window.to_s);
  return UnmappedMap(ClearedAlongRoute(world_teach.bundle.maps.front().grid, route, clutter),
                     nav::LikelihoodFieldConfig{}.occupied_threshold, route, clutter,
                     ClutterSite{}.robot_radius);
}

// The simulated scans of the window in `config`'s world, walked through the map and fitted.
UnmappedFit SimulatedUnmappedFit(const logs::LogIndex& index, const LogStreams& streams,
                                 const ModeTeach& world_teach,
                                 const std::filesystem::path& world_teach_dir,
                                 const LogWindow& window, const LogConfig& config,
                                 const UnmappedMap& unmapped, double sigma_hit, double mean_width) {
  const double range_min = index.scan.range_min;
  const double range_max = index.scan.range_max;
  const KnownRangeCaster caster(world_teach.bundle.maps.front().grid, range_max);
  std::vector<UnmappedBeam> beams;
  BandObservations observations = unmapped.NewObservations();
  try {
    SimulateScans(
        index, streams, world_teach, world_teach_dir, config, window,
        [&](double stamp, const core::Pose2& X_MR, const core::LaserScan& scan) {
          const core::Pose2 X_ML = X_MR * streams.robot.X_RL;
          for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
            const double r = scan.ranges[i];
            if (!(r >= range_min)) continue;
            const double a = X_ML.theta + scan.Angle(i);
            const core::Vec2 dir(std::cos(a), std::sin(a));
            const double z = r >= range_max ? std::numeric_limits<double>::infinity() : r;
            beams.push_back(unmapped.Walk(stamp, X_ML.translation(), dir, z,
                                          caster.Cast(X_ML.translation(), dir).map, &observations));
          }
        });
  } catch (const core::ConfigError& e) {
    // The placement's own advice (lower the density) does not apply to a measured density.
    const std::string what = e.detail().substr(0, e.detail().find("): "));
    throw core::ConfigError("clutter.kinds",
                            "the measured clutter (" + core::FormatNumber(config.clutter.density) +
                                " objects per m²) does not fit beside the log's route in the "
                                "simulator (" +
                                what +
                                ")): choose smaller kinds or a smaller "
                                "clutter.clearance");
  }
  unmapped.MarkStaticHits(observations, beams);
  // The simulated readings end on the world's faces: no hit offset.
  return FitUnmapped(beams, 3.0 * sigma_hit, 3.0 * sigma_hit, mean_width);
}

// The factor to scale a simulator value by: real / simulated; 2 when the simulation shows none
// of what the real scans show; 1 when the real scans show none (the value is 0 and stays 0).
double Ratio(double real, double simulated) {
  if (!(real > 0.0)) return 1.0;
  return simulated > 0.0 ? real / simulated : 2.0;
}

}  // namespace

WorldInference InferSimulatedWorld(const logs::LogIndex& index, const LogStreams& streams,
                                   const ModeTeach& world_teach,
                                   const std::filesystem::path& world_teach_dir,
                                   const LogWindow& window, const LidarCalibration& calibration,
                                   const ClutterConfig& clutter) {
  constexpr int kMaxSimulations = 8;
  constexpr double kFreePathTolerance = 0.05;
  // The density's estimate counts objects' hits: it moves in steps as objects come and go.
  constexpr double kDensityTolerance = 0.1;
  const UnmappedFit& real = calibration.unmapped_whole.fit;
  const nav::BeamMixture& mixture = calibration.whole.result.mixture;
  LogConfig config;
  config.sim.lidar.noise = WorldNoise(mixture);
  config.clutter = clutter;
  const UnmappedMap unmapped = WindowUnmappedMap(index, streams, world_teach, window, clutter);
  WorldInference out;
  out.unknown_hits_enough =
      std::min(calibration.unmapped_first_half.fit.unknown_hits,
               calibration.unmapped_second_half.fit.unknown_hits) >= kMinUnknownHitsPerHalf;
  // Rays that cross unknown cells farther than the LiDAR reaches meet nothing there: open.
  const double range_max = calibration.beams.range_max;
  out.free_path =
      out.unknown_hits_enough && real.unknown_free_path < range_max ? real.unknown_free_path : 0.0;
  out.density = real.density;
  while (out.simulations < kMaxSimulations) {
    config.sim.unknown_free_path = out.free_path;
    config.clutter.density = out.density;
    out.simulated = SimulatedUnmappedFit(index, streams, world_teach, world_teach_dir, window,
                                         config, unmapped, mixture.sigma_hit, real.mean_width_m);
    ++out.simulations;
    const double free_path_ratio =
        out.free_path > 0.0 ? Ratio(real.unknown_free_path, out.simulated.unknown_free_path) : 1.0;
    const double density_ratio = Ratio(real.density, out.simulated.density);
    if (std::abs(free_path_ratio - 1.0) <= kFreePathTolerance &&
        std::abs(density_ratio - 1.0) <= kDensityTolerance) {
      out.converged = true;
      break;
    }
    if (out.simulations == kMaxSimulations) break;
    out.free_path *= free_path_ratio;
    if (out.free_path >= range_max) out.free_path = 0.0;  // as open as a fill can make it
    out.density *= density_ratio;
  }
  return out;
}

CalibrationBeams CollectCalibrationBeams(const logs::LogIndex& index, const LogStreams& streams,
                                         const ModeTeach& world_teach, const LogWindow& window,
                                         const ClutterConfig& clutter) {
  if (streams.reference.empty()) {
    throw core::IoError(index.name +
                        ": no reference trajectory; calibration compares each beam with the "
                        "range the map predicts from where the robot was (give --reference "
                        "FILE.tum, or --synthetic-odometry for a corrected log whose poses are "
                        "the reference)");
  }
  CalibrationBeams beams;
  beams.range_min = index.scan.range_min;
  beams.range_max = index.scan.range_max;
  const KnownRangeCaster caster(world_teach.bundle.maps.front().grid, beams.range_max);
  const TeachMapTrace& trace = world_teach.trace.maps.front();
  const core::Pose2 X_MW = trace.X_MR.front() * trace.X_WR.front().Inverse();
  const UnmappedMap unmapped = WindowUnmappedMap(index, streams, world_teach, window, clutter);
  BandObservations observations = unmapped.NewObservations();
  logs::ReadScans(index, window.from_s, window.to_s, [&](const logs::ScanMessage& m, double t) {
    const std::optional<core::Pose2> X_WR = logs::PoseAt(streams.reference, m.scan.stamp);
    if (!X_WR) {
      ++beams.scans_without_reference;
      return;
    }
    if (beams.scans == 0) beams.first_s = t;
    beams.last_s = t;
    ++beams.scans;
    AddScanBeams(m.scan, t, X_MW * *X_WR * streams.robot.X_RL, caster, unmapped, &observations,
                 &beams);
  });
  unmapped.MarkStaticHits(observations, beams.unmapped);
  return beams;
}

LidarCalibration FitLidarCalibration(CalibrationBeams beams, const std::string& log_name,
                                     const LidarCalibrationOptions& options,
                                     const ClutterConfig& clutter) {
  const double middle = 0.5 * (beams.first_s + beams.last_s);
  const std::size_t split = static_cast<std::size_t>(
      std::lower_bound(beams.times.begin(), beams.times.end(), middle) - beams.times.begin());
  const std::size_t n = beams.samples.size();
  LidarCalibration out;
  out.first_half = FitPart(beams, 0, split, "first half of the window", log_name, options,
                           options.min_beams_per_half);
  out.second_half = FitPart(beams, split, n, "second half of the window", log_name, options,
                            options.min_beams_per_half);
  out.whole = FitPart(beams, 0, n, "whole window", log_name, options, 0);
  const nav::BeamMixture& m = out.whole.result.mixture;
  const double margin = 3.0 * m.sigma_hit - m.hit_offset;
  const double far_margin = 3.0 * m.sigma_hit + m.hit_offset;
  const double width = MeanClutterWidth(clutter);
  const auto part = [&](double from_s, double to_s) {
    const auto lo = std::lower_bound(beams.unmapped.begin(), beams.unmapped.end(), from_s,
                                     [](const UnmappedBeam& b, double t) { return b.t < t; });
    const auto hi = std::lower_bound(lo, beams.unmapped.end(), to_s,
                                     [](const UnmappedBeam& b, double t) { return b.t < t; });
    return UnmappedPart{FitUnmapped({lo, hi}, margin, far_margin, width), from_s, to_s};
  };
  out.unmapped_whole = part(beams.first_s, 1e300);
  out.unmapped_first_half = part(beams.first_s, middle);
  out.unmapped_second_half = part(middle, 1e300);
  out.unmapped_whole.to_s = out.unmapped_second_half.to_s = beams.last_s;
  out.beams = std::move(beams);
  return out;
}

sim::LidarNoiseConfig WorldNoise(const nav::BeamMixture& mixture) {
  sim::LidarNoiseConfig noise = NoiseOfMixture(mixture);
  noise.short_probability = 0.0;
  return noise;
}

sim::LidarNoiseConfig NoiseOfMixture(const nav::BeamMixture& mixture) {
  sim::LidarNoiseConfig noise;
  noise.sigma0 = mixture.sigma_hit;
  noise.sigma1 = 0.0;
  noise.dropout_probability = mixture.z_max;
  noise.short_probability = mixture.z_short;
  noise.short_lambda = mixture.lambda_short;
  noise.random_probability = mixture.z_rand;
  return noise;
}

}  // namespace retrace::bench
