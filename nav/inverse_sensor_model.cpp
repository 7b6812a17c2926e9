#include "nav/inverse_sensor_model.hpp"

#include <cmath>

#include "core/errors.hpp"
#include "core/occupancy_grid.hpp"

namespace retrace::nav {

void InverseSensorModelConfig::Validate() const {
  if (!(hit_probability > 0.5 && hit_probability < 1.0)) {
    throw core::ConfigError("hit_probability",
                            "must be in (0.5, 1), got " + core::FormatNumber(hit_probability));
  }
  if (!(miss_probability > 0.0 && miss_probability < 0.5)) {
    throw core::ConfigError("miss_probability",
                            "must be in (0, 0.5), got " + core::FormatNumber(miss_probability));
  }
  core::RequirePositive("sigma", sigma);
  core::RequireInRange("neighbourhood_sigmas", neighbourhood_sigmas, 0.0, 10.0);
}

InverseSensorModelConfig InverseModelFromLikelihoodField(double z_hit, double z_rand, double sigma,
                                                         double d_max, double range_max) {
  core::RequireInRange("z_hit", z_hit, 0.0, 1.0);
  core::RequireInRange("z_rand", z_rand, 0.0, 1.0);
  core::RequirePositive("sigma", sigma);
  core::RequireNonNegative("d_max", d_max);
  core::RequirePositive("range_max", range_max);
  const double floor =
      z_hit * std::exp(-d_max * d_max / (2.0 * sigma * sigma)) + z_rand / range_max;  // eq. (5)
  InverseSensorModelConfig config;
  config.hit_probability = z_hit + floor;  // d = 0: p_hit(0) = 1 without the normaliser
  config.miss_probability = floor;
  config.sigma = sigma;
  config.Validate();
  return config;
}

double SignedDistanceToEndPoint(double t_in, double t_out, double z) {
  if (t_out < z) return t_out - z;
  if (t_in > z) return t_in - z;
  return 0.0;
}

double OccupancyProbability(const InverseSensorModelConfig& config, double d) {
  const double reach = config.ReachBehind();
  if (d > reach) return 0.5;
  if (d < -reach) return config.miss_probability;
  const double hit = std::exp(-d * d / (2.0 * config.sigma * config.sigma));  // eq. (6)
  const double base = d < 0.0 ? config.miss_probability : 0.5;
  return base + (config.hit_probability - base) * hit;
}

double LogOddsUpdate(const InverseSensorModelConfig& config, double d) {
  return core::Logit(OccupancyProbability(config, d));  // eq. (4) with l0 = logit(0.5) = 0
}

double MissLogOdds(const InverseSensorModelConfig& config) {
  return core::Logit(config.miss_probability);
}

double HitLogOdds(const InverseSensorModelConfig& config) {
  return core::Logit(config.hit_probability);
}

}  // namespace retrace::nav
