#include "bench/engine/scheduler.hpp"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <numeric>
#include <set>
#include <tuple>

#include "bench/engine/parallel.hpp"
#include "bench/engine/playback.hpp"
#include "core/check.hpp"
#include "core/errors.hpp"

namespace retrace::bench {
namespace {

// A playback run ready to start, in the order runs are taken: the longest teaching drive first
// (its runs take longest), then by job, mode and run.
struct RunTask {
  double cost = 0.0;  // s: the job's teaching drive, which bounds its runs
  std::size_t job = 0;
  std::size_t mode = 0;
  int run = 0;
  bool operator<(const RunTask& o) const {
    return std::tie(o.cost, job, mode, run) < std::tie(cost, o.job, o.mode, o.run);
  }
};

// A task that threw, and where it stands in the queue's order: drives (by their position) before
// runs.
struct Failure {
  bool run = false;
  std::size_t drive_position = 0;
  RunTask task;
  std::exception_ptr error;
  bool operator<(const Failure& o) const {
    if (run != o.run) return !run;
    return run ? task < o.task : drive_position < o.drive_position;
  }
};

// The scheduler's state, shared by its worker threads under one mutex.
class EpisodeQueue {
 public:
  EpisodeQueue(std::vector<EpisodeJob>& jobs, int threads, ProgressSink* progress,
               const EpisodeCallbacks& callbacks);

  // A worker thread's loop: takes ready tasks until none is left or one has failed. Does not
  // throw: a task's error (its own or its callbacks') is kept for RethrowFirstFailure.
  void Work();
  // Rethrows the first failure in the queue's order, if any task failed.
  void RethrowFirstFailure() const;
  std::vector<TeachTiming> TakeTiming() { return std::move(timing_); }

 private:
  // The drive at this position of drives_ on `threads` threads, then its runs queued.
  void Drive(std::size_t position, int threads);
  void Play(const RunTask& task);
  void HandOverModesWithoutRuns(std::size_t job);
  void QueueRuns(std::size_t job);  // under mutex_
  void Fail(Failure failure);

  std::vector<EpisodeJob>& jobs_;
  ProgressSink* progress_;
  const EpisodeCallbacks& callbacks_;
  std::vector<TeachTiming> timing_;
  int threads_;
  std::vector<std::size_t> drives_;  // jobs to teach, longest route first (unknown routes last)
  std::vector<std::vector<int>> runs_left_;  // per job and mode

  std::mutex mutex_;
  std::condition_variable changed_;
  std::size_t next_drive_ = 0;
  std::size_t drives_done_ = 0;
  std::set<RunTask> ready_;
  int in_flight_ = 0;
  int busy_threads_ = 0;  // the threads the tasks in flight use (a drive may use several)
  int total_runs_ = 0;
  int runs_done_early_ = 0;  // runs done while drives still went on (before the playback phase)
  std::vector<Failure> failures_;
};

// Indices 0..n-1 ordered by decreasing cost (stable), so that the longest jobs start first.
std::vector<std::size_t> LongestFirst(const std::vector<double>& cost) {
  std::vector<std::size_t> order(cost.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return cost[a] > cost[b]; });
  return order;
}

// The scenario's route time at the teacher's speed; 0 before a loader ran.
double TeachCost(const EpisodeJob& job) {
  if (job.scenario == nullptr) return 0.0;
  return job.scenario->route_length / job.scenario->config.teach.teacher.speed;
}

// Runs `work`, prefixing the job's name to a core::Error it throws.
template <class Work>
auto Named(const EpisodeJob& job, const Work& work) {
  try {
    return work();
  } catch (const core::Error& e) {
    if (job.name.empty()) throw;
    throw core::Error(job.name + ": " + e.what());
  }
}

EpisodeQueue::EpisodeQueue(std::vector<EpisodeJob>& jobs, int threads, ProgressSink* progress,
                           const EpisodeCallbacks& callbacks)
    : jobs_(jobs),
      progress_(progress),
      callbacks_(callbacks),
      timing_(jobs.size()),
      threads_(std::max(threads, 1)),
      runs_left_(jobs.size()) {
  std::vector<std::size_t> teach;
  std::vector<double> cost;
  for (std::size_t j = 0; j < jobs_.size(); ++j) {
    EpisodeJob& job = jobs_[j];
    RETRACE_CHECK(job.scenario != nullptr || (job.load && job.taught.empty()));
    timing_[j].duration_s = job.taught_duration_s;
    if (job.taught.empty() && !job.modes.empty()) {
      teach.push_back(j);
      cost.push_back(TeachCost(job));
      total_runs_ += std::max(job.repeats, 0) * static_cast<int>(job.modes.size());
    } else {
      total_runs_ += std::max(job.repeats, 0) * static_cast<int>(job.taught.size());
    }
  }
  for (const std::size_t i : LongestFirst(cost)) drives_.push_back(teach[i]);
  // Jobs given their teach are taught already (no worker runs yet: no lock needed).
  for (std::size_t j = 0; j < jobs_.size(); ++j) {
    if (jobs_[j].taught.empty()) continue;
    HandOverModesWithoutRuns(j);
    QueueRuns(j);
  }
  if (progress_ && !drives_.empty()) progress_->Phase("teach", static_cast<int>(drives_.size()));
  if (progress_ && drives_.empty() && total_runs_ > 0) progress_->Phase("playback", total_runs_);
}

void EpisodeQueue::Work() {
  for (;;) {
    RunTask run;
    std::size_t drive = 0;
    bool is_run = false;
    int uses = 1;  // threads the task takes
    {
      std::unique_lock lock(mutex_);
      // A task starts only on a free thread: a drive given several keeps the other workers
      // waiting.
      changed_.wait(lock, [&] {
        return !failures_.empty() || in_flight_ == 0 ||
               (busy_threads_ < threads_ && (!ready_.empty() || next_drive_ < drives_.size()));
      });
      if (!failures_.empty()) return;
      if (!ready_.empty()) {
        run = *ready_.begin();
        ready_.erase(ready_.begin());
        is_run = true;
      } else if (next_drive_ < drives_.size()) {
        drive = next_drive_++;
        // The threads that would otherwise idle: those free now, less one for each drive still
        // to start (no runs are ready here). A drive that is the only task gets them all.
        uses = std::max(1, threads_ - busy_threads_ -
                               static_cast<int>(drives_.size() - next_drive_));
        // (no more than one per mode: a drive shares out its modes' recorders)
        uses = std::min(uses, std::max(1, static_cast<int>(jobs_[drives_[drive]].modes.size())));
      } else {
        return;  // nothing ready and nothing running that could make work: all done
      }
      ++in_flight_;
      busy_threads_ += uses;
    }
    try {
      if (is_run) {
        Play(run);
      } else {
        Drive(drive, uses);
      }
    } catch (...) {
      Fail(is_run ? Failure{true, 0, run, std::current_exception()}
                  : Failure{false, drive, {}, std::current_exception()});
    }
    {
      std::lock_guard lock(mutex_);
      --in_flight_;
      busy_threads_ -= uses;
    }
    changed_.notify_all();
  }
}

void EpisodeQueue::Drive(std::size_t position, int threads) {
  const std::size_t j = drives_[position];
  EpisodeJob& job = jobs_[j];
  Named(job, [&] {
    if (job.scenario == nullptr) job.scenario = job.load();
    std::unique_ptr<SensorTap> tap = callbacks_.tap ? callbacks_.tap(j, nullptr, -1) : nullptr;
    TeachResult teach =
        RunTeachDrive(*job.scenario, job.modes, SimTimeReporter(progress_), tap.get(), threads);
    job.taught = std::move(teach.modes);
    timing_[j] = {teach.duration_s, teach.cpu_time_s};
    HandOverModesWithoutRuns(j);
  });
  std::lock_guard lock(mutex_);
  QueueRuns(j);
  changed_.notify_all();
  if (!progress_) return;
  progress_->UnitDone();
  if (++drives_done_ == drives_.size() && total_runs_ > 0) {
    progress_->Phase("playback", total_runs_);
    for (int r = 0; r < runs_done_early_; ++r) progress_->UnitDone();
  }
}

// A mode without runs is done as soon as it is taught.
void EpisodeQueue::HandOverModesWithoutRuns(std::size_t j) {
  EpisodeJob& job = jobs_[j];
  if (job.repeats > 0 || !callbacks_.mode_done) return;
  for (std::size_t m = 0; m < job.taught.size(); ++m)
    callbacks_.mode_done(j, m, std::move(job.taught[m]));
}

void EpisodeQueue::QueueRuns(std::size_t j) {
  const EpisodeJob& job = jobs_[j];
  runs_left_[j].assign(job.taught.size(), std::max(job.repeats, 0));
  for (std::size_t m = 0; m < job.taught.size(); ++m) {
    for (int r = 0; r < job.repeats; ++r) ready_.insert({timing_[j].duration_s, j, m, r});
  }
}

void EpisodeQueue::Play(const RunTask& task) {
  EpisodeJob& job = jobs_[task.job];
  ModeTeach& teach = job.taught[task.mode];
  Named(job, [&] {
    std::unique_ptr<PlaybackObserver> observer =
        callbacks_.observe ? callbacks_.observe(teach, task.run) : nullptr;
    std::unique_ptr<SensorTap> tap =
        callbacks_.tap ? callbacks_.tap(task.job, &teach, task.run) : nullptr;
    RunTrace run = RunPlayback(*job.scenario, teach.bundle, teach.trace, task.run,
                               PlaybackTimeout(*job.scenario, timing_[task.job].duration_s),
                               SimTimeReporter(progress_), observer.get(), tap.get());
    if (callbacks_.run_done) callbacks_.run_done(task.job, task.mode, teach, std::move(run));
  });
  bool last = false;
  {
    std::lock_guard lock(mutex_);
    last = --runs_left_[task.job][task.mode] == 0;
    if (progress_ && drives_done_ < drives_.size()) {
      ++runs_done_early_;
    } else if (progress_) {
      progress_->UnitDone();
    }
  }
  // The last run of a (job, mode) hands its teach over, so that a caller can free it while
  // others still run.
  if (last && callbacks_.mode_done) {
    Named(job, [&] { callbacks_.mode_done(task.job, task.mode, std::move(teach)); });
  }
}

void EpisodeQueue::Fail(Failure failure) {
  {
    std::lock_guard lock(mutex_);
    failures_.push_back(std::move(failure));
  }
  changed_.notify_all();
}

void EpisodeQueue::RethrowFirstFailure() const {
  if (failures_.empty()) return;
  std::rethrow_exception(std::min_element(failures_.begin(), failures_.end())->error);
}

}  // namespace

std::vector<TeachTiming> RunEpisodes(std::vector<EpisodeJob> jobs, int threads,
                                     ProgressSink* progress, const EpisodeCallbacks& callbacks) {
  EpisodeQueue queue(jobs, threads, progress, callbacks);
  RunOnThreads(static_cast<std::size_t>(std::max(threads, 1)), [&queue] { queue.Work(); });
  queue.RethrowFirstFailure();
  return queue.TakeTiming();
}

}  // namespace retrace::bench
