#pragma once
// The probability that the estimate is right (docs/METHOD.md, "Reliability"), after the idea of
// Akai's Reliable MCL (J. Field Robotics 40(3), 2023), in a simpler form: a binary Bayes filter
// over "the estimate lies where the robot is", fed by each update's beam evidence at the
// estimate (nav/beam_evidence.hpp) and discounted by the distance driven.
//
//   prediction   log-odds(r) -= max_log_odds · d / hold_distance   for d metres driven since the
//                last update: a pose the scans no longer confirm goes wrong with the odometry's
//                drift, from the most confident to even odds over hold_distance;
//   measurement  log-odds(r) += n (f log(p_right / p_wrong) + (1 - f) log((1 - p_right) /
//                (1 - p_wrong))), where the evidence beams are the explained ones and those
//                that see through a mapped wall, f the explained share of them and n their
//                number, at most max_beams (the beams of one scan are far from independent);
//                then clamped to ±max_log_odds. Beams that end short of the map's walls or in
//                cells it never observed say nothing either way.
//
// So a belief whose beams are all rejected, or end in space the map never saw, loses confidence
// within hold_distance of driving; one that sees through mapped walls loses it within an update
// or two; and one that the scans support regains it as fast. The defaults fit Intel's first lap
// (docs/HISTORY.md, "Reliability"): at poses within 0.3 m of the truth the explained share's
// median is 0.89 and its 5 % quantile 0.64; at poses more than 1 m off, its median is 0.4.

#include "core/config.hpp"
#include "nav/beam_evidence.hpp"

namespace retrace::nav {

struct ReliabilityConfig {
  bool enabled = true;
  /// m of driving without evidence over which the log-odds fall from max_log_odds to 0
  double hold_distance = 4.0;
  double p_right = 0.85;  ///< an evidence beam is explained when the pose is right
  double p_wrong = 0.25;  ///< ... and when it is wrong (a corridor explains many poses)
  int max_beams = 10;     ///< evidence beams counted per update at most
  double max_log_odds = 5.0;  ///< the most confident: r = 0.993
  double threshold = 0.5;     ///< below it the localizer counts itself lost (unreliable)
  double initial = 0.9;       ///< after Initialize or a won recovery trial

  template <class V>
  void Reflect(V& v) {
    v("enabled", enabled);
    v("hold_distance", hold_distance);
    v("p_right", p_right);
    v("p_wrong", p_wrong);
    v("max_beams", max_beams);
    v("max_log_odds", max_log_odds);
    v("threshold", threshold);
    v("initial", initial);
  }
  /// Throws core::ConfigError naming the key: hold_distance > 0, 0 < p_wrong < p_right < 1,
  /// max_beams >= 1, max_log_odds > 0, threshold and initial in (0, 1).
  void Validate() const;
};

/// The filter: one value in (0, 1), updated once per measurement update.
class Reliability {
 public:
  explicit Reliability(const ReliabilityConfig& config = {});
  void Reset();
  /// After `driven` metres since the last update, with `evidence` at the estimate.
  double Update(const BeamEvidence& evidence, double driven);
  double value() const;
  /// Below the threshold (never while disabled).
  bool unreliable() const { return config_.enabled && value() < config_.threshold; }

 private:
  ReliabilityConfig config_;
  double log_odds_ = 0.0;
};

}  // namespace retrace::nav
