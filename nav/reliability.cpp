#include "nav/reliability.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace retrace::nav {

void ReliabilityConfig::Validate() const {
  core::RequirePositive("hold_distance", hold_distance);
  core::RequireInRange("p_wrong", p_wrong, 0.0, 1.0);
  core::RequireInRange("p_right", p_right, 0.0, 1.0);
  if (!(p_wrong > 0.0 && p_wrong < p_right && p_right < 1.0)) {
    throw core::ConfigError("p_right", "must satisfy 0 < p_wrong < p_right < 1");
  }
  core::RequireIntInRange("max_beams", max_beams, 1, 100'000);
  core::RequireInRange("threshold", threshold, 0.0, 1.0);
  core::RequireInRange("initial", initial, 0.0, 1.0);
  if (!(initial > 0.0 && initial < 1.0)) throw core::ConfigError("initial", "must be in (0, 1)");
}

double Reliability::Update(const BeamEvidence& evidence, double driven) {
  // Kept inside (0, 1) so that the log-odds stay finite: the scans can always bring it back.
  constexpr double kFloor = 1e-4;
  r_ = std::max(kFloor, r_ * std::exp(-std::max(0.0, driven) / config_.hold_distance));
  const int beams = evidence.explained + evidence.through_wall;
  if (beams > 0) {
    const double f = static_cast<double>(evidence.explained) / static_cast<double>(beams);
    const double n = std::min(beams, config_.max_beams);
    const double log_ratio =
        n * (f * std::log(config_.p_right / config_.p_wrong) +
             (1.0 - f) * std::log((1.0 - config_.p_right) / (1.0 - config_.p_wrong)));
    const double log_odds = std::log(r_ / (1.0 - r_)) + log_ratio;
    r_ = std::clamp(1.0 / (1.0 + std::exp(-log_odds)), kFloor, 1.0 - kFloor);
  }
  return r_;
}

}  // namespace retrace::nav
