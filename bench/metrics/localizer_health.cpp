#include "bench/metrics/localizer_health.hpp"

#include <cmath>

namespace retrace::bench {

LocalizerHealth ComputeLocalizerHealth(std::span<const EstimateSample> track,
                                       std::span<const LocalizerSample> updates) {
  LocalizerHealth h;
  for (std::size_t k = 0; k < track.size(); ++k) {
    const EstimateSample& s = track[k];
    if (s.lost && k + 1 < track.size()) h.lost_time_s += track[k + 1].time - s.time;
    if (k == 0) {
      h.lost_spells += s.lost ? 1 : 0;
      continue;
    }
    const EstimateSample& prev = track[k - 1];
    h.lost_spells += s.lost && !prev.lost ? 1 : 0;
    if (s.map != prev.map) continue;  // a switch moves the frame, not the estimate
    const core::Pose2 predicted = prev.X_MR * core::Between(prev.X_OR, s.X_OR);
    const double jump = core::Distance(predicted, s.X_MR);
    if (!(jump <= h.max_jump_m)) {  // also replaces the initial NaN
      h.max_jump_m = jump;
      h.max_jump_time_s = s.time;
    }
  }
  for (const LocalizerSample& u : updates) h.reacquisitions += u.reacquired ? 1 : 0;
  return h;
}

LocalizerHealth CombineLocalizerHealth(std::span<const LocalizerHealth> runs) {
  LocalizerHealth all;
  for (const LocalizerHealth& h : runs) {
    all.lost_time_s += h.lost_time_s;
    all.lost_spells += h.lost_spells;
    all.reacquisitions += h.reacquisitions;
    if (std::isfinite(h.max_jump_m) && !(h.max_jump_m <= all.max_jump_m)) {
      all.max_jump_m = h.max_jump_m;
      all.max_jump_time_s = h.max_jump_time_s;
    }
  }
  return all;
}

}  // namespace retrace::bench
