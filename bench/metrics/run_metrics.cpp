#include <algorithm>
#include <cmath>
#include <vector>

#include "bench/engine/local_truth.hpp"
#include "bench/metrics/internal/collisions.hpp"
#include "bench/metrics/internal/run_series.hpp"
#include "bench/metrics/internal/sample_stats.hpp"
#include "bench/metrics/internal/social.hpp"
#include "bench/metrics/metrics.hpp"

namespace retrace::bench {

using namespace internal;

namespace {

// The localizer's own account and its estimate's jumps (bench/metrics/localizer_health.hpp).
LocalizerHealth Health(const TeachTrace& teach, const RunTrace& run, const RunSeries& series) {
  std::vector<EstimateSample> track;
  track.reserve(run.samples.size());
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    const PlaybackSample& p = run.samples[i];
    track.push_back({p.time, p.map_index, p.X_MR, p.X_OR, p.lost, series.error_increase_m[i],
                     p.off_map, series.localization_error_m[i]});
  }
  LocalizerHealth h = ComputeLocalizerHealth(track, run.updates);
  h.wrong_switches = CountWrongSwitches(run.switches, teach);
  return h;
}

// Each switch's transformed estimate against the local truth at the start of the map entered.
void SwitchErrors(const RunTrace& run, TeachIndex& index, RunMetrics* m) {
  for (const SwitchRecord& sw : run.switches) {
    SwitchError e;
    e.time_s = sw.time;
    e.from = sw.from;
    e.to = sw.to;
    if (LocalTruth* matcher = index.Matcher(sw.to)) {
      matcher->Reset();
      const PoseError error = Compare(sw.X_MnR, matcher->InMap(sw.X_WR));
      e.error_m = error.distance;
      e.error_rad = error.angle;
      m->switch_error_max_m = MaxSkipNaN(m->switch_error_max_m, e.error_m);
      m->switch_error_max_rad = MaxSkipNaN(m->switch_error_max_rad, e.error_rad);
    }
    m->switches.push_back(e);
  }
}

// The dynamic-point totals and ratios, and the cost of the updates and of the run.
void UpdateTotals(const RunTrace& run, RunMetrics* m) {
  DynamicPointStats& d = m->dynamic_points;
  double cpu_sum_s = 0.0;
  for (const LocalizerSample& u : run.updates) {
    d.beams_tested += u.beams_tested;
    d.beams_rejected += u.beams_rejected;
    d.true_positive += u.true_positive;
    d.false_positive += u.false_positive;
    d.false_negative += u.false_negative;
    cpu_sum_s += u.cpu_s;
    m->cpu.localizer_update_max_ms = MaxSkipNaN(m->cpu.localizer_update_max_ms, 1e3 * u.cpu_s);
  }
  FinishDynamicPoints(d);
  m->cpu.localizer_updates = static_cast<int>(run.updates.size());
  if (!run.updates.empty()) {
    m->cpu.localizer_update_mean_ms = 1e3 * cpu_sum_s / static_cast<double>(run.updates.size());
  }
  m->cpu.sim_time_s = run.sim_time_s;
  m->cpu.cpu_time_s = run.cpu_time_s;
  m->cpu.real_time_factor =
      run.cpu_time_s > 0.0 ? run.sim_time_s / run.cpu_time_s : kMetricNaN;
}

}  // namespace

RunMetrics ComputeRunMetrics(const TeachTrace& teach, const RunTrace& run,
                             const MetricsConfig& config) {
  TeachIndex index(teach, config);
  const RunSeries series = Series(index, run, config, /*with_localization=*/true);

  RunMetrics m;
  m.run = run.run;
  m.seed = run.seed;
  m.outcome = run.outcome;
  m.success = run.outcome == Outcome::kSuccess;
  m.samples = static_cast<int>(run.samples.size());
  if (!run.samples.empty()) m.time_s = run.samples.back().time;
  for (std::size_t i = 1; i < run.samples.size(); ++i) {
    m.path_length_m += core::Distance(run.samples[i - 1].X_WR, run.samples[i].X_WR);
  }
  for (double s : series.progress_m) {
    if (std::isfinite(s)) m.progress_m = std::max(m.progress_m, std::min(s, index.path.length()));
  }
  m.tracking_error_m = Summarize(series.tracking_error_m);
  m.localization_error_m = Summarize(series.localization_error_m);
  m.localization_error_rad = Summarize(series.localization_error_rad);
  m.lost_fraction = FractionAbove(series.localization_error_m, config.lost_error);
  m.collisions = Collisions(run, config);
  m.localizer = Health(teach, run, series);
  SwitchErrors(run, index, &m);
  UpdateTotals(run, &m);
  const double taught_time_s = teach.time.empty() ? 0.0 : teach.time.back() - teach.time.front();
  m.social =
      Social(run, index.path.length(), taught_time_s, m.success, m.path_length_m, m.time_s, config);
  return m;
}

}  // namespace retrace::bench
