#include <algorithm>
#include <cmath>

#include "bench/metrics/internal/run_series.hpp"
#include "bench/metrics/internal/sample_stats.hpp"
#include "bench/metrics/internal/social.hpp"
#include "bench/metrics/metrics.hpp"

namespace retrace::bench {

using namespace internal;

namespace {

// Pooled over every sample of every run: the error summaries, the lost fraction and the
// repeatability.
void PoolSamples(TeachIndex& index, const std::vector<RunTrace>& runs,
                 const MetricsConfig& config, AggregateMetrics* a) {
  std::vector<RunSeries> series;
  std::vector<int> ids;
  std::vector<double> tracking, loc_m, loc_rad;
  for (const RunTrace& run : runs) {
    series.push_back(Series(index, run, config, /*with_localization=*/true));
    ids.push_back(run.run);
    const RunSeries& s = series.back();
    tracking.insert(tracking.end(), s.tracking_error_m.begin(), s.tracking_error_m.end());
    loc_m.insert(loc_m.end(), s.localization_error_m.begin(), s.localization_error_m.end());
    loc_rad.insert(loc_rad.end(), s.localization_error_rad.begin(), s.localization_error_rad.end());
  }
  a->tracking_error_m_pooled = Summarize(tracking);
  a->localization_error_m_pooled = Summarize(loc_m);
  a->localization_error_rad_pooled = Summarize(loc_rad);
  a->lost_fraction_pooled = FractionAbove(loc_m, config.lost_error);
  a->repeatability =
      RepeatabilityFromSeries(index.path.length(), index.path.empty(), ids, series, config);
}

// Outcomes, and the means over the runs of their times, lengths, progress, error summaries and
// lost fractions.
void AddRunMeans(const std::vector<RunMetrics>& metrics, AggregateMetrics* a) {
  std::vector<const Summary*> tracking_runs, loc_m_runs, loc_rad_runs;
  double time_sum = 0.0, length_sum = 0.0, progress_sum = 0.0, lost_sum = 0.0;
  int lost_runs = 0;
  for (const RunMetrics& m : metrics) {
    if (m.success) ++a->successes;
    const int outcome = static_cast<int>(m.outcome);
    if (outcome >= 0 && outcome < static_cast<int>(a->outcome_counts.size())) {
      ++a->outcome_counts[static_cast<std::size_t>(outcome)];
    }
    time_sum += m.time_s;
    length_sum += m.path_length_m;
    progress_sum += m.progress_m;
    tracking_runs.push_back(&m.tracking_error_m);
    loc_m_runs.push_back(&m.localization_error_m);
    loc_rad_runs.push_back(&m.localization_error_rad);
    if (std::isfinite(m.lost_fraction)) {
      lost_sum += m.lost_fraction;
      ++lost_runs;
    }
  }
  if (a->runs > 0) {
    a->success_rate = static_cast<double>(a->successes) / a->runs;
    a->mean_time_s = time_sum / a->runs;
    a->mean_path_length_m = length_sum / a->runs;
    a->mean_progress_m = progress_sum / a->runs;
  }
  a->tracking_error_m_run_mean = MeanOfSummaries(tracking_runs);
  a->localization_error_m_run_mean = MeanOfSummaries(loc_m_runs);
  a->localization_error_rad_run_mean = MeanOfSummaries(loc_rad_runs);
  if (lost_runs > 0) a->lost_fraction_run_mean = lost_sum / lost_runs;
}

void AddCollisions(const std::vector<RunMetrics>& metrics, AggregateMetrics* a) {
  CollisionStats& c = a->collisions;
  for (const RunMetrics& m : metrics) {
    c.static_incidents += m.collisions.static_incidents;
    c.pedestrian_incidents += m.collisions.pedestrian_incidents;
    c.pedestrian_incidents_robot_driving += m.collisions.pedestrian_incidents_robot_driving;
    c.static_events += m.collisions.static_events;
    c.pedestrian_events += m.collisions.pedestrian_events;
    c.min_clearance_m = MinSkipNaN(c.min_clearance_m, m.collisions.min_clearance_m);
    c.min_pedestrian_gap_m = MinSkipNaN(c.min_pedestrian_gap_m, m.collisions.min_pedestrian_gap_m);
    if (m.collisions.static_incidents + m.collisions.pedestrian_incidents > 0) {
      ++a->runs_with_collision;
    }
  }
}

// Every finite switch error of every run: count, mean and max.
void AddSwitchErrors(const std::vector<RunMetrics>& metrics, AggregateMetrics* a) {
  double sum_m = 0.0, sum_rad = 0.0;
  for (const RunMetrics& m : metrics) {
    for (const SwitchError& e : m.switches) {
      if (!std::isfinite(e.error_m) || !std::isfinite(e.error_rad)) continue;
      ++a->switch_error.count;
      sum_m += e.error_m;
      sum_rad += e.error_rad;
      a->switch_error.max_m = MaxSkipNaN(a->switch_error.max_m, e.error_m);
      a->switch_error.max_rad = MaxSkipNaN(a->switch_error.max_rad, e.error_rad);
    }
  }
  if (a->switch_error.count > 0) {
    a->switch_error.mean_m = sum_m / a->switch_error.count;
    a->switch_error.mean_rad = sum_rad / a->switch_error.count;
  }
}

void AddDynamicPointsAndCpu(const std::vector<RunMetrics>& metrics, AggregateMetrics* a) {
  double update_ms_sum = 0.0;
  for (const RunMetrics& m : metrics) {
    DynamicPointStats& d = a->dynamic_points;
    d.beams_tested += m.dynamic_points.beams_tested;
    d.beams_rejected += m.dynamic_points.beams_rejected;
    d.true_positive += m.dynamic_points.true_positive;
    d.false_positive += m.dynamic_points.false_positive;
    d.false_negative += m.dynamic_points.false_negative;
    a->cpu.localizer_updates += m.cpu.localizer_updates;
    if (m.cpu.localizer_updates > 0) {
      update_ms_sum += m.cpu.localizer_update_mean_ms * m.cpu.localizer_updates;
    }
    a->cpu.localizer_update_max_ms =
        MaxSkipNaN(a->cpu.localizer_update_max_ms, m.cpu.localizer_update_max_ms);
    a->cpu.sim_time_s += m.cpu.sim_time_s;
    a->cpu.cpu_time_s += m.cpu.cpu_time_s;
  }
  FinishDynamicPoints(a->dynamic_points);
  if (a->cpu.localizer_updates > 0) {
    a->cpu.localizer_update_mean_ms = update_ms_sum / a->cpu.localizer_updates;
  }
  a->cpu.real_time_factor =
      a->cpu.cpu_time_s > 0.0 ? a->cpu.sim_time_s / a->cpu.cpu_time_s : kMetricNaN;
}

}  // namespace

AggregateMetrics Aggregate(const TeachTrace& teach, const std::vector<RunTrace>& runs,
                           const std::vector<RunMetrics>& metrics, const MetricsConfig& config) {
  RETRACE_CHECK(runs.size() == metrics.size());
  AggregateMetrics a;
  TeachIndex index(teach, config);
  a.runs = static_cast<int>(runs.size());
  a.taught_path_length_m = index.path.length();
  PoolSamples(index, runs, config, &a);
  std::vector<LocalizerHealth> health;
  for (const RunMetrics& m : metrics) health.push_back(m.localizer);
  a.localizer = CombineLocalizerHealth(health);
  AddRunMeans(metrics, &a);
  AddCollisions(metrics, &a);
  AddSwitchErrors(metrics, &a);
  AddDynamicPointsAndCpu(metrics, &a);
  a.social = AggregateSocial(metrics);
  return a;
}

}  // namespace retrace::bench
