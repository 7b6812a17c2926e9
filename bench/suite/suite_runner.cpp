#include "bench/suite/suite_runner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "bench/engine/parallel.hpp"
#include "bench/engine/scheduler.hpp"
#include "bench/metrics/experiment.hpp"
#include "bench/metrics/flat_metrics.hpp"
#include "bench/metrics/metrics.hpp"
#include "core/errors.hpp"

namespace retrace::bench {
namespace {

std::string Where(const SuiteSpec& spec, const SuiteEntry& entry) {
  return spec.source.string() + ":" + std::to_string(entry.line) + ": entry '" + entry.name + "': ";
}

}  // namespace

double MeanOfDefined(const std::vector<double>& values) {
  double sum = 0.0;
  int count = 0;
  for (double v : values) {
    if (std::isfinite(v)) {
      sum += v;
      ++count;
    }
  }
  return count > 0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

SuiteScenarios LoadSuiteScenarios(const SuiteSpec& spec,
                                  const std::vector<io::ConfigOverride>& extra, int jobs) {
  struct Job {
    std::size_t entry;
    std::size_t seed;
  };
  // The suite decides the seeds and the runs per seed; an override of either would be
  // silently replaced below, so it is refused.
  auto refuse = [&](const io::ConfigOverride& o, const std::string& where) {
    if (o.key_path == "seed" || o.key_path == "playback.repeats") {
      throw core::ConfigError(
          o.key_path,
          where + "cannot set " + o.key_path + ": a suite entry's `seeds` and `repeats` decide it",
          true);
    }
  };
  for (const io::ConfigOverride& o : extra) refuse(o, "--set " + o.key_path + "=" + o.value + ": ");
  for (const SuiteEntry& entry : spec.entries) {
    for (const io::ConfigOverride& o : entry.overrides) refuse(o, Where(spec, entry));
  }
  std::vector<Job> loads;
  SuiteScenarios out;
  out.scenarios.resize(spec.entries.size());
  for (std::size_t e = 0; e < spec.entries.size(); ++e) {
    out.scenarios[e].resize(spec.entries[e].seeds.size());
    for (std::size_t s = 0; s < spec.entries[e].seeds.size(); ++s) loads.push_back({e, s});
  }
  // Loading builds the worlds and checks the routes: worth a few threads on big worlds.
  // ParallelFor rethrows the first error by job index, so the message does not depend on timing.
  ParallelFor(jobs > 0 ? jobs : DefaultJobs(), loads.size(), [&](std::size_t i) {
    const SuiteEntry& entry = spec.entries[loads[i].entry];
    std::vector<io::ConfigOverride> overrides = entry.overrides;
    overrides.insert(overrides.end(), extra.begin(), extra.end());
    overrides.push_back({"seed", std::to_string(entry.seeds[loads[i].seed])});
    overrides.push_back({"playback.repeats", std::to_string(entry.repeats)});
    Scenario scenario;
    try {
      scenario = LoadScenario(entry.scenario, overrides);
    } catch (const core::ConfigError& e) {
      throw core::ConfigError(e.key_path(), Where(spec, entry) + e.what(), true);
    } catch (const core::IoError& e) {
      throw core::IoError(Where(spec, entry) + e.what());
    } catch (const core::WorldError& e) {
      throw core::WorldError(Where(spec, entry) + e.what());
    }
    scenario.config.modes = entry.modes;
    out.scenarios[loads[i].entry][loads[i].seed] = std::move(scenario);
  });
  return out;
}

namespace {

// One job of the suite: an (entry, seed), one teaching drive, then `repeats` runs per mode.
struct SuiteUnit {
  std::size_t entry;
  std::size_t seed;
};

// What a unit's mode keeps: its runs until the last one is done, then only its flat aggregate,
// so that memory holds the traces of the modes still running.
struct SuiteSlot {
  std::vector<RunTrace> runs;
  std::vector<RunMetrics> run_metrics;
  std::map<std::string, double> aggregate;
};

// The suite's jobs, one per (entry, seed), and their units.
std::vector<EpisodeJob> SuiteEpisodes(const SuiteSpec& spec, const SuiteScenarios& scenarios,
                                      std::vector<SuiteUnit>* units) {
  std::vector<EpisodeJob> episodes;
  for (std::size_t e = 0; e < spec.entries.size(); ++e) {
    for (std::size_t s = 0; s < spec.entries[e].seeds.size(); ++s) {
      const Scenario& scenario = scenarios.scenarios[e][s];
      units->push_back({e, s});
      EpisodeJob job;
      job.scenario = &scenario;
      job.modes = scenario.config.modes;
      job.repeats = scenario.config.playback.repeats;
      episodes.push_back(std::move(job));
    }
  }
  return episodes;
}

// Per entry and mode, the seeds' values and their mean.
SuiteResults CollectSuiteResults(const SuiteSpec& spec, const std::vector<SuiteUnit>& units,
                                 const std::vector<std::vector<SuiteSlot>>& slots) {
  SuiteResults results;
  for (std::size_t u = 0; u < units.size(); ++u) {
    const SuiteEntry& entry = spec.entries[units[u].entry];
    for (std::size_t m = 0; m < entry.modes.size(); ++m) {
      const std::string prefix =
          entry.name + "." + std::string(core::EnumName(entry.modes[m])) + ".";
      for (const auto& [name, value] : slots[u][m].aggregate) {
        SuiteMetric& metric = results.metrics[prefix + name];
        metric.per_seed.resize(entry.seeds.size(), std::numeric_limits<double>::quiet_NaN());
        metric.per_seed[units[u].seed] = value;
      }
    }
  }
  for (auto& [name, metric] : results.metrics) metric.mean = MeanOfDefined(metric.per_seed);
  return results;
}

}  // namespace

SuiteResults RunSuite(const SuiteSpec& spec, const SuiteScenarios& scenarios, int jobs,
                      ProgressSink* progress) {
  std::vector<SuiteUnit> units;
  std::vector<EpisodeJob> episodes = SuiteEpisodes(spec, scenarios, &units);
  std::vector<std::vector<SuiteSlot>> slots(units.size());
  int playback_runs = 0;
  for (std::size_t u = 0; u < units.size(); ++u) {
    const auto repeats = static_cast<std::size_t>(episodes[u].repeats);
    slots[u].resize(episodes[u].modes.size());
    for (SuiteSlot& slot : slots[u]) {
      slot.runs.resize(repeats);
      slot.run_metrics.resize(repeats);
      playback_runs += static_cast<int>(repeats);
    }
  }
  const auto scenario_of = [&](std::size_t u) -> const Scenario& {
    return scenarios.scenarios[units[u].entry][units[u].seed];
  };
  EpisodeCallbacks callbacks;
  callbacks.run_done = [&](std::size_t u, std::size_t m, const ModeTeach& teach, RunTrace&& run) {
    SuiteSlot& slot = slots[u][m];
    const auto i = static_cast<std::size_t>(run.run);
    slot.run_metrics[i] = ComputeRunMetrics(teach.trace, run, scenario_of(u).config.metrics);
    slot.runs[i] = std::move(run);
  };
  callbacks.mode_done = [&](std::size_t u, std::size_t m, ModeTeach&& teach) {
    SuiteSlot& slot = slots[u][m];
    slot.aggregate = FlatMetrics(AggregateMode(scenario_of(u), teach, slot.runs, slot.run_metrics));
    slot.runs = {};
    slot.run_metrics = {};
  };
  RunEpisodes(std::move(episodes), jobs, progress, callbacks);

  SuiteResults results = CollectSuiteResults(spec, units, slots);
  results.teaching_drives = static_cast<int>(units.size());
  results.playback_runs = playback_runs;
  return results;
}

}  // namespace retrace::bench
