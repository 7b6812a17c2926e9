#pragma once
// One localizer update as the metrics keep it (LocalizerSample), for playback and log replay
// alike: the beams tested and rejected, the belief's spread, a re-acquisition, the cost, and,
// where the source knows which beams hit a pedestrian (the simulator), the dynamic-point mask
// scored against that.

#include <span>

#include "bench/engine/trace.hpp"
#include "nav/localizer.hpp"
#include "sim/lidar.hpp"

namespace retrace::bench {

/// `truth`: per scan beam, what produced it (empty for a log: no true/false positives).
LocalizerSample ScoreUpdate(const nav::LocalizerUpdate& update, double time, double cpu_s,
                            std::span<const sim::BeamTruth> truth);

}  // namespace retrace::bench
