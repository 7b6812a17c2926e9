#pragma once
// The one scheduler of episodes. `retrace run`, `playback`, `bench`, `sweep` and `compare` all
// run through it. Its work is a queue of tasks: a job's teaching drive (after loading the job's
// scenario, when the job brings a loader) and each of its playback runs, which become ready when
// the drive is done. A free thread takes the runs of taught jobs before it starts another
// teaching drive, so that a job's maps and traces are freed as early as possible and memory holds
// about one job per thread; within each kind, the longest first, so that a long route does not
// leave cores idle at the end. A teaching drive is given the threads that would otherwise idle
// (those free when it starts, less one per drive still to start, at most one per mode) for its
// modes' recorders (RunTeachDrive), and a task starts only on a free thread. Each run is seeded by
// its own index (PlaybackRng), and a drive's bundles do not depend on its threads, so the results
// do not depend on the number of threads or on which thread ran what.

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bench/engine/playback_observer.hpp"
#include "bench/engine/progress.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/sensor_tap.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/engine/trace.hpp"

namespace retrace::bench {

/// One teaching drive (or teach folders read back) and its playback runs in every mode.
struct EpisodeJob {
  const Scenario* scenario = nullptr;  ///< must outlive the call
  /// Instead of `scenario`: loads it on a worker thread right before the job's teaching drive
  /// (only for a job that teaches). The scenario must outlive the job's last callback.
  std::function<const Scenario*()> load;
  /// Prefixed to the message of a core::Error that the job's load, teaching drive or runs throw
  /// (e.g. "case 12 (particles=300, repeat 0, seed 1)"); empty: the message as it is.
  std::string name;
  std::vector<MapMode> modes;  ///< modes to teach; ignored when `taught` is given
  /// Already taught modes (e.g. teach folders read back): no teaching drive then.
  std::vector<ModeTeach> taught;
  double taught_duration_s = 0.0;  ///< with `taught`: the teaching drive's duration (s)
  int repeats = 0;                 ///< playback runs per mode
};

struct EpisodeCallbacks {
  /// A playback run finished: `job`, the index of its mode in the job, the mode's teach and
  /// the run's trace (its `run` field says which). Called from a worker thread: write only the
  /// slot of (job, mode, run).
  std::function<void(std::size_t job, std::size_t mode, const ModeTeach& teach, RunTrace&& run)>
      run_done;
  /// Every run of (job, mode) finished (right after teaching when repeats is 0): the mode's
  /// teach is handed over. Called once per (job, mode), from a worker thread, after all of its
  /// run_done calls.
  std::function<void(std::size_t job, std::size_t mode, ModeTeach&& teach)> mode_done;
  /// Optional: an observer of run `run` (nullptr: none), e.g. a video recorder.
  std::function<std::unique_ptr<PlaybackObserver>(const ModeTeach& teach, int run)> observe;
  /// Optional: a sensor tap (nullptr: none) for job `job`'s teaching drive (`teach` nullptr) or
  /// its run `run` of a mode, e.g. a log recorder. Called from a worker thread.
  std::function<std::unique_ptr<SensorTap>(std::size_t job, const ModeTeach* teach, int run)> tap;
};

/// A job's teaching drive: how long it took in simulated time and on its thread's CPU (0 for a
/// job given its teach).
struct TeachTiming {
  double duration_s = 0.0;
  double cpu_time_s = 0.0;
};

/// Runs the jobs on `threads` threads (>= 1) and returns each job's teach timing. Progress: a
/// "teach" phase of the drives (when any job teaches), then a "playback" phase of all runs (runs
/// done while drives still went on count when it starts). Throws core::WorldError when a
/// teaching drive cannot finish its route or the world refuses a run's start. After an error no
/// task starts; of the tasks that failed, the first in the queue's order (drives before runs,
/// then longest first) is rethrown.
std::vector<TeachTiming> RunEpisodes(std::vector<EpisodeJob> jobs, int threads,
                                     ProgressSink* progress, const EpisodeCallbacks& callbacks);

}  // namespace retrace::bench
