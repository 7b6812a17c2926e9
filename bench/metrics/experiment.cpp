#include "bench/metrics/experiment.hpp"

#include <algorithm>

#include "bench/engine/parallel.hpp"
#include "bench/engine/scheduler.hpp"
#include "bench/metrics/map_quality.hpp"

namespace retrace::bench {
namespace {

// Runs the jobs through the one scheduler and measures every run; jobs[i] -> result[i].
std::vector<Experiment> Run(std::vector<EpisodeJob> jobs, const ExperimentOptions& options) {
  const auto repeats = static_cast<std::size_t>(std::max(options.repeats, 0));
  std::vector<Experiment> experiments(jobs.size());
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    jobs[j].repeats = static_cast<int>(repeats);
    const std::size_t modes = jobs[j].taught.empty() ? jobs[j].modes.size() : jobs[j].taught.size();
    experiments[j].modes.resize(modes);
    for (ModeResult& mode : experiments[j].modes) {
      mode.runs.resize(repeats);
      mode.run_metrics.resize(repeats);
    }
  }
  std::vector<const Scenario*> scenarios;
  for (const EpisodeJob& job : jobs) scenarios.push_back(job.scenario);

  EpisodeCallbacks callbacks;
  callbacks.run_done = [&](std::size_t j, std::size_t m, const ModeTeach& teach, RunTrace&& run) {
    ModeResult& mode = experiments[j].modes[m];
    const auto i = static_cast<std::size_t>(run.run);
    mode.run_metrics[i] = ComputeRunMetrics(teach.trace, run, scenarios[j]->config.metrics);
    mode.runs[i] = std::move(run);
  };
  callbacks.mode_done = [&](std::size_t j, std::size_t m, ModeTeach&& teach) {
    ModeResult& mode = experiments[j].modes[m];
    mode.teach = std::move(teach);
    if (repeats > 0)
      mode.aggregate = AggregateMode(*scenarios[j], mode.teach, mode.runs, mode.run_metrics);
  };
  callbacks.observe = options.observe;
  if (options.tap) {
    callbacks.tap = [&](std::size_t, const ModeTeach* teach, int run) {
      return options.tap(teach, run);
    };
  }
  const std::vector<TeachTiming> timing =
      RunEpisodes(std::move(jobs), options.jobs, options.progress, callbacks);
  for (std::size_t j = 0; j < experiments.size(); ++j) {
    experiments[j].teach_duration_s = timing[j].duration_s;
    experiments[j].teach_cpu_time_s = timing[j].cpu_time_s;
  }
  return experiments;
}

}  // namespace

AggregateMetrics AggregateMode(const Scenario& scenario, const ModeTeach& teach,
                               const std::vector<RunTrace>& runs,
                               const std::vector<RunMetrics>& run_metrics) {
  AggregateMetrics aggregate = Aggregate(teach.trace, runs, run_metrics, scenario.config.metrics);
  aggregate.map_quality =
      ComputeMapQuality(teach, scenario.teach_world.geometry,
                        scenario.config.nav.localizer.likelihood_field.occupied_threshold);
  aggregate.switching = EvaluateSwitching(teach.trace, scenario.config.route.revisit_radius,
                                          SwitchReasons(teach, scenario.config.route),
                                          scenario.config.route.OnlineSwitching().MinMapLength());
  aggregate.match_counts = teach.match_counts;
  return aggregate;
}

Experiment RunPlaybacks(const Scenario& scenario, std::vector<ModeTeach> teaches,
                        double teach_duration_s, const ExperimentOptions& options) {
  std::vector<EpisodeJob> jobs(1);
  jobs[0].scenario = &scenario;
  jobs[0].taught = std::move(teaches);
  jobs[0].taught_duration_s = teach_duration_s;
  return std::move(Run(std::move(jobs), options).front());
}

Experiment RunExperiment(const Scenario& scenario, const std::vector<MapMode>& modes,
                         const ExperimentOptions& options) {
  return std::move(RunExperiments({&scenario}, modes, options).front());
}

std::vector<Experiment> RunExperiments(const std::vector<const Scenario*>& scenarios,
                                       const std::vector<MapMode>& modes,
                                       const ExperimentOptions& options) {
  std::vector<EpisodeJob> jobs(scenarios.size());
  for (std::size_t j = 0; j < scenarios.size(); ++j) {
    jobs[j].scenario = scenarios[j];
    jobs[j].modes = modes;
  }
  return Run(std::move(jobs), options);
}

ExperimentOptions RunOptionsFor(int repeats, int jobs, ProgressSink* progress) {
  ExperimentOptions options;
  options.repeats = repeats;
  options.jobs = jobs > 0 ? jobs : DefaultJobs();
  options.progress = progress;
  return options;
}

}  // namespace retrace::bench
