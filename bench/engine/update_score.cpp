#include "bench/engine/update_score.hpp"

namespace retrace::bench {

LocalizerSample ScoreUpdate(const nav::LocalizerUpdate& update, double time, double cpu_s,
                            std::span<const sim::BeamTruth> truth) {
  LocalizerSample sample;
  sample.time = time;
  sample.cpu_s = cpu_s;
  sample.beams_tested = update.beams_tested;
  sample.beams_rejected = update.beams_rejected;
  sample.spread = update.spread;
  sample.rejection_particles = update.rejection_particles;
  sample.reacquired = update.reacquired;
  sample.lost = update.lost;
  sample.beams_used = update.beams_used;
  sample.trial_updates = update.trial_updates;
  sample.trial_log_bayes_factor = update.trial_log_bayes_factor;
  sample.evidence = update.evidence;
  sample.reliability = update.reliability;
  if (truth.empty()) return sample;
  for (std::size_t i = 0; i < update.beams.size(); ++i) {
    if (update.beams[i] == nav::BeamUse::kUnused) continue;
    const bool rejected = update.beams[i] == nav::BeamUse::kRejected;
    const bool pedestrian = truth[i].source == sim::BeamSource::kPedestrian;
    if (rejected && pedestrian) ++sample.true_positive;
    if (rejected && !pedestrian) ++sample.false_positive;
    if (!rejected && pedestrian) ++sample.false_negative;
  }
  return sample;
}

}  // namespace retrace::bench
