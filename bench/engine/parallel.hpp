#pragma once
// The threads every parallel part of the harness runs on: RunOnThreads starts and joins them;
// ParallelFor hands them independent jobs (e.g. loading the scenarios of a sweep or a suite to
// check them before anything runs), and the episode scheduler (bench/engine/scheduler.hpp) its
// queue of teaching drives and runs. Each job writes only its own result slot, so the results do
// not depend on the number of threads or on which thread ran what.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace retrace::bench {

/// The default number of worker threads: the machine's cores (at least 1).
inline int DefaultJobs() {
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

/// Calls worker() on `threads` threads (threads <= 1: once, in this thread) and waits for all.
/// worker must not throw.
template <class Worker>
void RunOnThreads(std::size_t threads, const Worker& worker) {
  if (threads <= 1) {
    worker();
    return;
  }
  std::vector<std::thread> pool;
  for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
}

/// Calls job(i) for i in [0, count) on up to `jobs` threads (jobs <= 1: in this thread, in
/// order). If jobs throw, the first exception (by job index) is rethrown after all threads end;
/// jobs not yet started are skipped.
template <class Job>
void ParallelFor(int jobs, std::size_t count, const Job& job) {
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  auto worker = [&] {
    for (std::size_t i = next++; i < count && !failed; i = next++) {
      try {
        job(i);
      } catch (...) {
        errors[i] = std::current_exception();
        failed = true;
      }
    }
  };
  RunOnThreads(std::min<std::size_t>(static_cast<std::size_t>(std::max(jobs, 1)), count), worker);
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace retrace::bench
