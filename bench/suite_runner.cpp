#include "bench/suite_runner.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>

#include "bench/episode.hpp"
#include "bench/experiment.hpp"
#include "bench/metrics.hpp"
#include "bench/parallel.hpp"
#include "bench/progress.hpp"
#include "bench/teach_drive.hpp"
#include "core/errors.hpp"

namespace retrace::bench {
namespace {

std::string Where(const SuiteSpec& spec, const SuiteEntry& entry) {
  return spec.source.string() + ":" + std::to_string(entry.line) + ": entry '" + entry.name + "': ";
}

// Indices 0..n-1 ordered by decreasing cost (stable), so that the longest jobs start first.
std::vector<std::size_t> LongestFirst(const std::vector<double>& cost) {
  std::vector<std::size_t> order(cost.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return cost[a] > cost[b]; });
  return order;
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

SuiteResults RunSuite(const SuiteSpec& spec, const SuiteScenarios& scenarios, int jobs,
                      ProgressLine* progress) {
  // A unit is one (entry, seed): one teaching drive, then repeats runs per mode.
  struct Unit {
    std::size_t entry;
    std::size_t seed;
    const Scenario* scenario;
  };
  std::vector<Unit> units;
  for (std::size_t e = 0; e < spec.entries.size(); ++e) {
    for (std::size_t s = 0; s < spec.entries[e].seeds.size(); ++s)
      units.push_back({e, s, &scenarios.scenarios[e][s]});
  }

  // Teaching drives, the longest route (in time) first.
  std::vector<TeachResult> teaches(units.size());
  std::vector<double> teach_cost(units.size());
  for (std::size_t u = 0; u < units.size(); ++u) {
    const ScenarioConfig& c = units[u].scenario->config;
    teach_cost[u] = units[u].scenario->route_length / c.teach.teacher.speed;
  }
  const std::vector<std::size_t> teach_order = LongestFirst(teach_cost);
  if (progress) progress->Phase("teach", static_cast<int>(units.size()));
  ParallelFor(jobs, units.size(), [&](std::size_t i) {
    const std::size_t u = teach_order[i];
    teaches[u] = RunTeachDrive(*units[u].scenario, units[u].scenario->config.modes,
                               SimTimeReporter(progress));
    if (progress) progress->UnitDone();
  });

  // Playback runs of every unit and mode, the longest teaching drive first. The last run of a
  // (unit, mode) to finish aggregates it and frees its traces and maps, so that memory holds
  // only the modes still running.
  struct Task {
    std::size_t unit;
    std::size_t mode;
    int run;
  };
  std::vector<Task> tasks;
  std::vector<double> run_cost;
  std::vector<std::size_t> slot_base(units.size());  // index of (unit, mode 0) in the slots
  std::size_t slots = 0;
  for (std::size_t u = 0; u < units.size(); ++u) {
    slot_base[u] = slots;
    const int repeats = units[u].scenario->config.playback.repeats;
    for (std::size_t m = 0; m < teaches[u].modes.size(); ++m, ++slots) {
      for (int r = 0; r < repeats; ++r) {
        tasks.push_back({u, m, r});
        run_cost.push_back(teaches[u].duration_s);
      }
    }
  }
  std::vector<std::vector<RunTrace>> runs(slots);
  std::vector<std::vector<RunMetrics>> run_metrics(slots);
  std::vector<std::map<std::string, double>> aggregates(slots);
  std::vector<std::atomic<int>> remaining(slots);
  for (std::size_t u = 0; u < units.size(); ++u) {
    const int repeats = units[u].scenario->config.playback.repeats;
    for (std::size_t m = 0; m < teaches[u].modes.size(); ++m) {
      runs[slot_base[u] + m].resize(static_cast<std::size_t>(repeats));
      run_metrics[slot_base[u] + m].resize(static_cast<std::size_t>(repeats));
      remaining[slot_base[u] + m].store(repeats);
    }
  }

  const std::vector<std::size_t> run_order = LongestFirst(run_cost);
  if (progress) progress->Phase("playback", static_cast<int>(tasks.size()));
  ParallelFor(jobs, tasks.size(), [&](std::size_t i) {
    const Task& task = tasks[run_order[i]];
    const Scenario& scenario = *units[task.unit].scenario;
    ModeTeach& teach = teaches[task.unit].modes[task.mode];
    const std::size_t slot = slot_base[task.unit] + task.mode;
    const double timeout = PlaybackTimeout(scenario, teaches[task.unit].duration_s);
    const auto run = static_cast<std::size_t>(task.run);
    runs[slot][run] = RunPlayback(scenario, teach.bundle, teach.trace, task.run, timeout,
                                  SimTimeReporter(progress));
    run_metrics[slot][run] =
        ComputeRunMetrics(teach.trace, runs[slot][run], scenario.config.metrics);
    if (remaining[slot].fetch_sub(1) == 1) {
      aggregates[slot] = FlatMetrics(
          Aggregate(teach.trace, runs[slot], run_metrics[slot], scenario.config.metrics));
      runs[slot] = {};
      run_metrics[slot] = {};
      teach = {};
    }
    if (progress) progress->UnitDone();
  });

  // Per entry and mode, the seeds' values and their mean.
  SuiteResults results;
  results.teaching_drives = static_cast<int>(units.size());
  results.playback_runs = static_cast<int>(tasks.size());
  for (std::size_t u = 0; u < units.size(); ++u) {
    const SuiteEntry& entry = spec.entries[units[u].entry];
    for (std::size_t m = 0; m < entry.modes.size(); ++m) {
      const std::string prefix =
          entry.name + "." + std::string(core::EnumName(entry.modes[m])) + ".";
      for (const auto& [name, value] : aggregates[slot_base[u] + m]) {
        SuiteMetric& metric = results.metrics[prefix + name];
        metric.per_seed.resize(entry.seeds.size(), std::numeric_limits<double>::quiet_NaN());
        metric.per_seed[units[u].seed] = value;
      }
    }
  }
  for (auto& [name, metric] : results.metrics) metric.mean = MeanOfDefined(metric.per_seed);
  return results;
}

}  // namespace retrace::bench
