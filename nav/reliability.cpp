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
  core::RequirePositive("max_log_odds", max_log_odds);
  core::RequireInRange("threshold", threshold, 0.0, 1.0);
  core::RequireInRange("initial", initial, 0.0, 1.0);
  if (!(initial > 0.0 && initial < 1.0)) throw core::ConfigError("initial", "must be in (0, 1)");
}

Reliability::Reliability(const ReliabilityConfig& config) : config_(config) { Reset(); }

void Reliability::Reset() { log_odds_ = std::log(config_.initial / (1.0 - config_.initial)); }

double Reliability::value() const { return 1.0 / (1.0 + std::exp(-log_odds_)); }

double Reliability::Update(const BeamEvidence& evidence, double driven) {
  const double m = config_.max_log_odds;
  log_odds_ -= m * std::max(0.0, driven) / config_.hold_distance;
  const int beams = evidence.explained + evidence.through_wall;
  if (beams > 0) {
    const double f = static_cast<double>(evidence.explained) / static_cast<double>(beams);
    const double n = std::min(beams, config_.max_beams);
    log_odds_ += n * (f * std::log(config_.p_right / config_.p_wrong) +
                      (1.0 - f) * std::log((1.0 - config_.p_right) / (1.0 - config_.p_wrong)));
  }
  // Bounded both ways: the scans can always bring it back, and take it away.
  log_odds_ = std::clamp(log_odds_, -m, m);
  return value();
}

}  // namespace retrace::nav
