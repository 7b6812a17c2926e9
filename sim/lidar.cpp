#include "sim/lidar.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/angle.hpp"
#include "core/check.hpp"
#include "core/errors.hpp"
#include "core/limits.hpp"

namespace retrace::sim {
namespace {

constexpr double kNoReturn = std::numeric_limits<double>::infinity();

void RequireProbability(std::string_view key, double p) { core::RequireInRange(key, p, 0.0, 1.0); }

const LidarConfig& Validated(const LidarConfig& config) {
  config.Validate();
  return config;
}

// A double range in [range_min, range_max] as a float that still lies in that interval (the
// nearest float may round across a limit that is not a float itself).
float ToReading(double r, double range_min, double range_max) {
  float f = static_cast<float>(r);
  if (static_cast<double>(f) > range_max) f = std::nextafter(f, 0.0f);
  if (static_cast<double>(f) < range_min) f = std::nextafter(f, std::numeric_limits<float>::max());
  return f;
}

// A short return in [lo, hi) (m): uniform when lambda is 0, else the exponential density
// lambda exp(-lambda z) truncated to the interval, by inverting its distribution function. One
// uniform draw either way.
double DrawShortReturn(double lo, double hi, double lambda, core::Rng& rng) {
  if (lambda == 0.0) return rng.Uniform(lo, hi);
  const double u = rng.Uniform();
  // z = lo - log(1 - u (1 - exp(-lambda (hi - lo)))) / lambda, in the stable log1p/expm1 form.
  const double z = lo - std::log1p(u * std::expm1(-lambda * (hi - lo))) / lambda;
  return std::clamp(z, lo, hi);
}

// The beam's truth from its static geometry at `wall` and its nearest pedestrian (or
// range_max) at `limit` (m); returns the true range (m, +inf without a return).
double BeamTruthRange(double wall, double limit, BeamTruth* truth) {
  double t = kNoReturn;
  if (wall <= limit) {
    t = wall;
    truth->pedestrian_id = -1;
    truth->source = BeamSource::kStatic;
  } else if (truth->pedestrian_id >= 0) {
    t = limit;
    truth->source = BeamSource::kPedestrian;
  } else {
    truth->source = BeamSource::kNothing;
  }
  truth->range = t;
  return t;
}

// The reading of one beam whose static geometry lies at `wall` and whose nearest pedestrian (or
// range_max) at `limit` (m), with the dropouts, spurious returns and range noise of `noise`;
// sets the beam's truth (its pedestrian_id as the pedestrians left it).
float ReadLidarBeam(double wall, double limit, const LidarNoiseConfig& noise, double range_min,
                    double range_max, BeamTruth* truth, core::Rng& rng) {
  const double p_drop = noise.dropout_probability;
  const double p_short_end = p_drop + noise.short_probability;
  const double p_event = p_short_end + noise.random_probability;
  const bool noisy = noise.sigma0 > 0.0 || noise.sigma1 > 0.0;
  const double t = BeamTruthRange(wall, limit, truth);

  // One uniform draw per beam decides dropout / short / random / regular, whatever the
  // geometry (none when every event has probability 0).
  const double u = p_event > 0.0 ? rng.Uniform() : 1.0;
  if (u < p_drop) {
    truth->source = BeamSource::kDropout;
    return std::numeric_limits<float>::infinity();
  }
  if (u < p_short_end) {
    const double upper = std::min(t, range_max);
    if (upper > range_min) {
      truth->source = BeamSource::kSpurious;
      return ToReading(DrawShortReturn(range_min, upper, noise.short_lambda, rng), range_min,
                       range_max);
    }
  } else if (u < p_event) {
    truth->source = BeamSource::kSpurious;
    return ToReading(rng.Uniform(range_min, range_max), range_min, range_max);
  }
  if (t == kNoReturn) return std::numeric_limits<float>::infinity();
  double r = t;
  if (noisy) r += (noise.sigma0 + noise.sigma1 * t) * rng.Normal();
  if (r > range_max) return std::numeric_limits<float>::infinity();
  if (r < range_min) return -std::numeric_limits<float>::infinity();
  return ToReading(r, range_min, range_max);
}

}  // namespace

void LidarNoiseConfig::Validate() const {
  core::RequireNonNegative("sigma0", sigma0);
  core::RequireNonNegative("sigma1", sigma1);
  RequireProbability("dropout_probability", dropout_probability);
  RequireProbability("short_probability", short_probability);
  core::RequireNonNegative("short_lambda", short_lambda);
  RequireProbability("random_probability", random_probability);
  if (dropout_probability + short_probability > 1.0) {
    throw core::ConfigError("short_probability",
                            "dropout_probability + short_probability must not exceed 1");
  }
  if (dropout_probability + short_probability + random_probability > 1.0) {
    throw core::ConfigError(
        "random_probability",
        "dropout_probability + short_probability + random_probability must not exceed 1");
  }
}

void LidarConfig::Validate() const {
  if (!(fov_deg > 0.0 && fov_deg <= 360.0)) {
    throw core::ConfigError("fov_deg", "must be in (0, 360], got " + core::FormatNumber(fov_deg));
  }
  core::RequireIntInRange("beams", beams, 2, core::kMaxBeams);
  core::RequireNonNegative("range_min", range_min);
  core::RequirePositive("range_max", range_max);
  core::RequireGreater("range_max", range_max, "range_min", range_min);
  core::RequirePositive("rate_hz", rate_hz);
  if (!std::isfinite(mount.x) || !std::isfinite(mount.y) || !std::isfinite(mount.theta)) {
    throw core::ConfigError("mount", "must be finite [x, y, theta]");
  }
  try {
    noise.Validate();
  } catch (const core::ConfigError& e) {
    throw core::ConfigError("noise." + e.key_path(), e.detail());
  }
}

Lidar::Lidar(const LidarConfig& config, const StaticGeometry& geometry)
    : config_(Validated(config)), caster_(geometry) {
  const double fov = core::DegToRad(config_.fov_deg);
  angle_min_ = -0.5 * fov;
  angle_increment_ = fov / static_cast<double>(config_.beams - 1);
  beam_dirs_L_.reserve(static_cast<std::size_t>(config_.beams));
  for (int i = 0; i < config_.beams; ++i) {
    // Same formula as core::LaserScan::Angle, so consumers see the beams where they were cast.
    const double a = angle_min_ + static_cast<double>(i) * angle_increment_;
    beam_dirs_L_.emplace_back(std::cos(a), std::sin(a));
  }
}

void Lidar::AddObstacles(const StaticGeometry& solids) {
  std::size_t ring_edges = 0;
  for (const auto& ring : solids.polygons()) ring_edges += ring.size();
  RETRACE_CHECK(ring_edges == solids.segments().size() && solids.masks().empty());
  for (const auto& ring : solids.polygons()) {
    Obstacle o;
    Vec2 center = Vec2::Zero();
    for (const Vec2& v : ring) center += v;
    center /= static_cast<double>(ring.size());
    double radius = 0.0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      radius = std::max(radius, (ring[i] - center).norm());
      o.edges.push_back({ring[i], ring[(i + 1) % ring.size()]});
    }
    o.bound = {center, radius};
    obstacle_parts_.push_back(std::move(o));
    obstacles_.AddPolygon(ring);
  }
  for (const Circle& circle : solids.circles()) {
    RETRACE_CHECK(circle.center.allFinite() && circle.radius > 0.0);
    obstacle_parts_.push_back({circle, {}, circle});
    obstacles_.AddCircle(circle);
  }
}

// The beams of one scan in W: the LiDAR's position, its heading (cos, sin) and the beams'
// unit directions, and which beams can meet a disc.
struct Lidar::ScanBeams {
  Vec2 origin;
  double c, s;
  std::vector<Vec2> dirs;
  double range_max, angle_min, angle_increment;
  int last_beam;

  // Calls test_beams(lo, hi) for beam index intervals that together hold every beam that can
  // meet a disc (centre and radius in W): the disc's angular interval seen from L, widened by
  // one beam against rounding, in each 2 pi wrap. The exact hit tests decide.
  template <class TestBeams>
  void ForCovered(const Vec2& center, double radius, const TestBeams& test_beams) const {
    const Vec2 rel = center - origin;
    const double dist = rel.norm();
    if (dist - radius > range_max) return;
    if (dist <= radius) {  // the sensor is inside: every beam may meet the boundary
      test_beams(0, last_beam);
      return;
    }
    const double half = std::asin(radius / dist);
    const double bearing = std::atan2(-s * rel.x() + c * rel.y(), c * rel.x() + s * rel.y());
    for (const double wrap : {-2.0 * core::kPi, 0.0, 2.0 * core::kPi}) {
      const double lo = (bearing + wrap - half - angle_min) / angle_increment;
      const double hi = (bearing + wrap + half - angle_min) / angle_increment;
      if (hi < -1.0 || lo > static_cast<double>(last_beam) + 1.0) continue;
      // Clamped before the conversion so that huge indices (tiny increments) stay in int.
      test_beams(
          std::max(static_cast<int>(std::ceil(std::max(lo, -1.0))) - 1, 0),
          std::min(static_cast<int>(std::floor(std::min(hi, last_beam + 1.0))) + 1, last_beam));
    }
  }
};

Lidar::ScanBeams Lidar::BeamsFrom(const core::Pose2& X_WL) const {
  const std::size_t n = beam_dirs_L_.size();
  ScanBeams beams{X_WL.translation(),   std::cos(X_WL.theta),   std::sin(X_WL.theta),
                  std::vector<Vec2>(n), config_.range_max,      angle_min_,
                  angle_increment_,     static_cast<int>(n) - 1};
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& d = beam_dirs_L_[i];
    beams.dirs[i] = Vec2(beams.c * d.x() - beams.s * d.y(), beams.s * d.x() + beams.c * d.y());
  }
  return beams;
}

void Lidar::HitPedestrians(const ScanBeams& beams, std::span<const DynamicCircle> pedestrians,
                           std::span<double> limit, std::span<BeamTruth> truth) {
  for (const DynamicCircle& p : pedestrians) {
    RETRACE_CHECK(p.id >= 0 && p.radius > 0.0 && std::isfinite(p.center.x()) &&
                  std::isfinite(p.center.y()));
    const Circle circle{p.center, p.radius};
    beams.ForCovered(p.center, p.radius, [&](int lo, int hi) {
      for (int i = lo; i <= hi; ++i) {
        const auto k = static_cast<std::size_t>(i);
        const double t = RayCircleHit(beams.origin, beams.dirs[k], circle);
        // Ties keep the earlier pedestrian; the first one exactly at range_max still counts.
        if (t < limit[k] || (t == limit[k] && truth[k].pedestrian_id < 0)) {
          limit[k] = t;
          truth[k].pedestrian_id = p.id;
        }
      }
    });
  }
}

void Lidar::CastStatic(const ScanBeams& beams, std::span<const double> limit,
                       std::span<double> wall) const {
  const std::size_t n = beams.dirs.size();
  if (obstacle_parts_.empty()) {
    caster_.CastFan(beams.origin, beams.dirs, limit, wall);
    return;
  }
  std::vector<double> added(n, kNoReturn);
  for (const Obstacle& o : obstacle_parts_) {
    beams.ForCovered(o.bound.center, o.bound.radius, [&](int lo, int hi) {
      for (int i = lo; i <= hi; ++i) {
        const auto k = static_cast<std::size_t>(i);
        double t = kNoReturn;
        if (o.edges.empty()) {
          t = RayCircleHit(beams.origin, beams.dirs[k], o.circle);
        } else {
          for (const Segment& e : o.edges) {
            t = std::min(t, RaySegmentHit(beams.origin, beams.dirs[k], e));
          }
        }
        if (t <= beams.range_max) added[k] = std::min(added[k], t);
      }
    });
  }
  std::vector<double> cast_limit(n);
  for (std::size_t i = 0; i < n; ++i) cast_limit[i] = std::min(limit[i], added[i]);
  caster_.CastFan(beams.origin, beams.dirs, cast_limit, wall);
  for (std::size_t i = 0; i < n; ++i) wall[i] = std::min(wall[i], added[i]);
}

LidarReading Lidar::Scan(const core::Pose2& X_WR, std::span<const DynamicCircle> pedestrians,
                         double stamp, core::Rng& rng) const {
  const std::size_t n = beam_dirs_L_.size();
  const double range_min = config_.range_min;
  const double range_max = config_.range_max;

  LidarReading out;
  out.scan.stamp = stamp;
  out.scan.angle_min = angle_min_;
  out.scan.angle_increment = angle_increment_;
  out.scan.range_min = range_min;
  out.scan.range_max = range_max;
  out.scan.ranges.resize(n);
  out.truth.resize(n);
  const ScanBeams beams = BeamsFrom(X_WR * config_.mount);

  // Pedestrians first, each on the beams it can cover.
  std::vector<double> limit(n, range_max);
  for (auto& t : out.truth) t.pedestrian_id = -1;
  HitPedestrians(beams, pedestrians, limit, out.truth);
  // Static geometry up to the nearest pedestrian (or range_max): a wall at the same distance
  // as a pedestrian wins the tie. Added obstacles are static too: their closest hit within
  // range_max also bounds the ray caster's search.
  std::vector<double> wall(n);
  CastStatic(beams, limit, wall);
  for (std::size_t i = 0; i < n; ++i) {
    out.scan.ranges[i] =
        ReadLidarBeam(wall[i], limit[i], config_.noise, range_min, range_max, &out.truth[i], rng);
  }
  return out;
}

}  // namespace retrace::sim
