#include "bench/experiment.hpp"

#include <limits>
#include <nlohmann/json.hpp>

#include "bench/episode.hpp"
#include "bench/parallel.hpp"
#include "bench/progress.hpp"

namespace retrace::bench {
namespace {

void Flatten(const nlohmann::json& node, const std::string& prefix,
             std::map<std::string, double>& out) {
  if (node.is_object()) {
    for (const auto& [key, value] : node.items())
      Flatten(value, prefix.empty() ? key : prefix + "." + key, out);
  } else if (node.is_number()) {
    out[prefix] = node.get<double>();
  } else if (node.is_null()) {
    out[prefix] = std::numeric_limits<double>::quiet_NaN();
  } else if (node.is_boolean()) {
    out[prefix] = node.get<bool>() ? 1.0 : 0.0;
  }
  // arrays and strings carry no single number
}

}  // namespace

Experiment RunPlaybacks(const Scenario& scenario, std::vector<ModeTeach> teaches,
                        double teach_duration_s, const ExperimentOptions& options) {
  Experiment experiment;
  experiment.teach_duration_s = teach_duration_s;
  const std::size_t repeats = static_cast<std::size_t>(std::max(options.repeats, 0));
  for (ModeTeach& teach : teaches) {
    ModeResult mode;
    mode.teach = std::move(teach);
    mode.runs.resize(repeats);
    mode.run_metrics.resize(repeats);
    experiment.modes.push_back(std::move(mode));
  }
  const std::size_t total = experiment.modes.size() * repeats;
  if (total == 0) return experiment;

  const double timeout = PlaybackTimeout(scenario, teach_duration_s);
  if (options.progress) options.progress->Phase("playback", static_cast<int>(total));
  ParallelFor(options.jobs, total, [&](std::size_t i) {
    ModeResult& mode = experiment.modes[i / repeats];
    const std::size_t run = i % repeats;
    std::unique_ptr<PlaybackObserver> observer =
        options.observe ? options.observe(mode.teach, static_cast<int>(run)) : nullptr;
    mode.runs[run] =
        RunPlayback(scenario, mode.teach.bundle, mode.teach.trace, static_cast<int>(run), timeout,
                    SimTimeReporter(options.progress), observer.get());
    mode.run_metrics[run] =
        ComputeRunMetrics(mode.teach.trace, mode.runs[run], scenario.config.metrics);
    if (options.progress) options.progress->UnitDone();
  });
  for (ModeResult& mode : experiment.modes) {
    mode.aggregate =
        Aggregate(mode.teach.trace, mode.runs, mode.run_metrics, scenario.config.metrics);
  }
  return experiment;
}

Experiment RunExperiment(const Scenario& scenario, const std::vector<MapMode>& modes,
                         const ExperimentOptions& options) {
  if (options.progress) options.progress->Phase("teach", 1);
  TeachResult teach = RunTeachDrive(scenario, modes, SimTimeReporter(options.progress));
  return RunPlaybacks(scenario, std::move(teach.modes), teach.duration_s, options);
}

std::map<std::string, double> FlatMetrics(const AggregateMetrics& aggregate) {
  std::map<std::string, double> out;
  Flatten(ToJson(aggregate), "", out);
  return out;
}

bool IsTimingMetric(const std::string& name) { return name.rfind("cpu.", 0) == 0; }

}  // namespace retrace::bench
