#pragma once
// One measured experiment: the teaching drive of a scenario (or teach folders read back), the
// playback runs of every map mode (bench/engine/scheduler.hpp), then their metrics. `retrace
// run` writes it to a results folder; comparisons and sweeps keep only its numbers.

#include <functional>
#include <memory>
#include <vector>

#include "bench/engine/playback_observer.hpp"
#include "bench/engine/progress.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/engine/trace.hpp"
#include "bench/metrics/metrics.hpp"

namespace retrace::bench {

/// The playback runs of one map mode and their metrics.
struct ModeResult {
  ModeTeach teach;
  std::vector<RunTrace> runs;           ///< run i at index i
  std::vector<RunMetrics> run_metrics;  ///< ComputeRunMetrics of runs[i]
  AggregateMetrics aggregate;           ///< over `runs`; meaningful only when runs is not empty
};

struct Experiment {
  double teach_duration_s = 0.0;  ///< simulated
  double teach_cpu_time_s = 0.0;  ///< of the teaching drive, on its thread (0: teach given)
  std::vector<ModeResult> modes;  ///< in the order of the teaches
};

struct ExperimentOptions {
  int repeats = 0;                   ///< playback runs per mode (0: teach only)
  int jobs = 1;                      ///< worker threads for the runs
  ProgressSink* progress = nullptr;  ///< optional
  /// Optional: an observer for run `run` of a mode (nullptr: none), e.g. a video recorder.
  std::function<std::unique_ptr<PlaybackObserver>(const ModeTeach& teach, int run)> observe;
  /// Optional: a sensor tap of the teaching drive (`teach` nullptr) or of run `run` of a mode.
  std::function<std::unique_ptr<SensorTap>(const ModeTeach* teach, int run)> tap;
};

/// Options for `repeats` playback runs per mode on `jobs` threads (0: one per core), reporting
/// to `progress` (may be null).
ExperimentOptions RunOptionsFor(int repeats, int jobs, ProgressSink* progress);

/// The metrics of one mode: Aggregate over its runs, plus the quality of its taught maps
/// against the scenario's teach world and its scan-matching counts. Every path from runs to a
/// mode's numbers (experiments, suites) goes through here.
AggregateMetrics AggregateMode(const Scenario& scenario, const ModeTeach& teach,
                               const std::vector<RunTrace>& runs,
                               const std::vector<RunMetrics>& run_metrics);

/// Teaches the scenario's route for `modes` with one drive, then plays back. Results do not
/// depend on options.jobs. Throws core::WorldError for a route the teacher cannot drive.
Experiment RunExperiment(const Scenario& scenario, const std::vector<MapMode>& modes,
                         const ExperimentOptions& options);

/// Several experiments of the same modes (e.g. the seeds of a study) through the one scheduler:
/// all their teaching drives, then all their playback runs, so that the cores stay busy;
/// result i belongs to scenarios[i] (which must outlive the call).
std::vector<Experiment> RunExperiments(const std::vector<const Scenario*>& scenarios,
                                       const std::vector<MapMode>& modes,
                                       const ExperimentOptions& options);

/// Plays back already taught maps (e.g. a teach folder read back); `teach_duration_s` sets the
/// playback timeout.
Experiment RunPlaybacks(const Scenario& scenario, std::vector<ModeTeach> teaches,
                        double teach_duration_s, const ExperimentOptions& options);

}  // namespace retrace::bench
