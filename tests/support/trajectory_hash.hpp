#pragma once
// A hash of a playback run's trajectories (time, ground truth and estimate at every control
// tick), for determinism tests: equal hashes mean bit-identical runs.

#include <cstdint>

#include "bench/engine/trace.hpp"
#include "core/rng.hpp"

namespace retrace::testing {

inline std::uint64_t TrajectoryHash(const bench::RunTrace& run) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const bench::PlaybackSample& s : run.samples) {
    const double values[] = {s.time,   s.X_WR.x, s.X_WR.y,    s.X_WR.theta,
                             s.X_MR.x, s.X_MR.y, s.X_MR.theta};
    h = core::HashBytes(values, sizeof values, h);
  }
  return h;
}

}  // namespace retrace::testing
