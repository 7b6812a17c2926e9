#pragma once
// The calling thread's CPU time, for the cost metrics; never used to decide anything in an
// episode (docs/DESIGN.md §3: no clock steers a run).

#include <time.h>

namespace retrace::bench {

/// Thread CPU time (s) since the thread started.
inline double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace retrace::bench
