#pragma once
// One experiment: the teaching drive of a scenario (or teach folders read back), then the
// playback runs of every map mode in parallel, then their metrics. `retrace run` writes it to
// a results folder; suites, sweeps and comparisons (bench/suite*, bench/sweep*, bench/compare*)
// only keep its numbers.

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench/metrics.hpp"
#include "bench/playback_observer.hpp"
#include "bench/progress.hpp"
#include "bench/scenario.hpp"
#include "bench/teach_drive.hpp"
#include "bench/trace.hpp"

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
  std::vector<ModeResult> modes;  ///< in the order of the teaches
};

struct ExperimentOptions {
  int repeats = 0;                 ///< playback runs per mode (0: teach only)
  int jobs = 1;                    ///< worker threads for the runs
  ProgressLine* progress = nullptr;  ///< optional
  /// Optional: an observer for run `run` of a mode (nullptr: none), e.g. a video recorder.
  std::function<std::unique_ptr<PlaybackObserver>(const ModeTeach& teach, int run)> observe;
};

/// Teaches the scenario's route for `modes` with one drive, then plays back. Results do not
/// depend on options.jobs. Throws core::WorldError for a route the teacher cannot drive.
Experiment RunExperiment(const Scenario& scenario, const std::vector<MapMode>& modes,
                         const ExperimentOptions& options);

/// Plays back already taught maps (e.g. a teach folder read back); `teach_duration_s` sets the
/// playback timeout.
Experiment RunPlaybacks(const Scenario& scenario, std::vector<ModeTeach> teaches, double teach_duration_s,
                        const ExperimentOptions& options);

/// Every number of ToJson(aggregate) by its dotted path, e.g. "success_rate",
/// "tracking_error_m.pooled.rms", "switch_error.max_m", "cpu.real_time_factor". null (NaN)
/// values are NaN; arrays are left out.
std::map<std::string, double> FlatMetrics(const AggregateMetrics& aggregate);

/// True for the metrics that measure the machine rather than the navigation (cpu.*): they are
/// reported, never compared against a baseline.
bool IsTimingMetric(const std::string& name);

}  // namespace retrace::bench
