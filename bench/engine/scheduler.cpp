#include "bench/engine/scheduler.hpp"

#include <algorithm>
#include <atomic>
#include <numeric>

#include "bench/engine/parallel.hpp"
#include "bench/engine/playback.hpp"

namespace retrace::bench {
namespace {

// Indices 0..n-1 ordered by decreasing cost (stable), so that the longest jobs start first.
std::vector<std::size_t> LongestFirst(const std::vector<double>& cost) {
  std::vector<std::size_t> order(cost.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return cost[a] > cost[b]; });
  return order;
}

}  // namespace

std::vector<TeachTiming> RunEpisodes(std::vector<EpisodeJob> jobs, int threads,
                                     ProgressSink* progress, const EpisodeCallbacks& callbacks) {
  // Teaching drives, the longest route (in time) first.
  std::vector<std::size_t> to_teach;
  std::vector<double> teach_cost;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    if (!jobs[j].taught.empty() || jobs[j].modes.empty()) continue;
    to_teach.push_back(j);
    const Scenario& s = *jobs[j].scenario;
    teach_cost.push_back(s.route_length / s.config.teach.teacher.speed);
  }
  std::vector<TeachTiming> timing(jobs.size());
  for (std::size_t j = 0; j < jobs.size(); ++j) timing[j].duration_s = jobs[j].taught_duration_s;
  if (!to_teach.empty()) {
    const std::vector<std::size_t> order = LongestFirst(teach_cost);
    if (progress) progress->Phase("teach", static_cast<int>(to_teach.size()));
    ParallelFor(threads, to_teach.size(), [&](std::size_t i) {
      EpisodeJob& job = jobs[to_teach[order[i]]];
      const std::size_t j = to_teach[order[i]];
      std::unique_ptr<SensorTap> tap = callbacks.tap ? callbacks.tap(j, nullptr, -1) : nullptr;
      TeachResult teach =
          RunTeachDrive(*job.scenario, job.modes, SimTimeReporter(progress), tap.get());
      job.taught = std::move(teach.modes);
      timing[to_teach[order[i]]] = {teach.duration_s, teach.cpu_time_s};
      if (progress) progress->UnitDone();
    });
  }

  // Playback runs of every job and mode, the longest teaching drive first. The last run of a
  // (job, mode) hands its teach over, so that a caller can free it while others still run.
  struct Task {
    std::size_t job;
    std::size_t mode;
    int run;
  };
  std::vector<Task> tasks;
  std::vector<double> run_cost;
  std::vector<std::vector<std::atomic<int>>> remaining(jobs.size());
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    remaining[j] = std::vector<std::atomic<int>>(jobs[j].taught.size());
    for (std::size_t m = 0; m < jobs[j].taught.size(); ++m) {
      remaining[j][m].store(jobs[j].repeats);
      if (jobs[j].repeats <= 0 && callbacks.mode_done)
        callbacks.mode_done(j, m, std::move(jobs[j].taught[m]));
      for (int r = 0; r < jobs[j].repeats; ++r) {
        tasks.push_back({j, m, r});
        run_cost.push_back(timing[j].duration_s);
      }
    }
  }
  if (tasks.empty()) return timing;

  const std::vector<std::size_t> order = LongestFirst(run_cost);
  if (progress) progress->Phase("playback", static_cast<int>(tasks.size()));
  ParallelFor(threads, tasks.size(), [&](std::size_t i) {
    const Task& task = tasks[order[i]];
    EpisodeJob& job = jobs[task.job];
    ModeTeach& teach = job.taught[task.mode];
    std::unique_ptr<PlaybackObserver> observer =
        callbacks.observe ? callbacks.observe(teach, task.run) : nullptr;
    std::unique_ptr<SensorTap> tap =
        callbacks.tap ? callbacks.tap(task.job, &teach, task.run) : nullptr;
    RunTrace run = RunPlayback(*job.scenario, teach.bundle, teach.trace, task.run,
                               PlaybackTimeout(*job.scenario, timing[task.job].duration_s),
                               SimTimeReporter(progress), observer.get(), tap.get());
    if (callbacks.run_done) callbacks.run_done(task.job, task.mode, teach, std::move(run));
    if (remaining[task.job][task.mode].fetch_sub(1) == 1 && callbacks.mode_done)
      callbacks.mode_done(task.job, task.mode, std::move(teach));
    if (progress) progress->UnitDone();
  });
  return timing;
}

}  // namespace retrace::bench
