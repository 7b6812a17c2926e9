// The social metrics broken down by the behaviour toward the robot of the people met
// (docs/DESIGN.md §6 and metrics.hpp: by_behaviour, stopped_by).

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>

#include "bench/metrics/internal/sample_stats.hpp"
#include "bench/metrics/internal/social.hpp"

namespace retrace::bench::internal {
namespace {

constexpr std::size_t kBehaviours = core::EnumTraits<sim::RobotBehaviour>::kNames.size();

// Who stopped a failed run: per behaviour, the time reacting people of it spent in the robot's
// personal zone during the run's last kStoppedByWindow; the behaviour with the most, if any.
std::optional<sim::RobotBehaviour> StoppedBy(const RunTrace& run, const std::vector<double>& dt,
                                             const MetricsConfig& config) {
  const std::vector<PlaybackSample>& samples = run.samples;
  if (samples.empty()) return std::nullopt;
  const double from = samples.back().time - kStoppedByWindow;
  std::array<double, kBehaviours> time{};
  std::size_t k = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    std::array<bool, kBehaviours> in_zone{};
    for (; k < run.nearby.size() && run.nearby[k].sample == static_cast<int>(i); ++k) {
      const NearbyPedestrian& n = run.nearby[k];
      const double gap =
          (n.position - samples[i].X_WR.translation()).norm() - n.radius - run.robot_radius;
      if (n.reacting && gap < config.personal_zone)
        in_zone[static_cast<std::size_t>(n.behaviour)] = true;
    }
    if (samples[i].time < from) continue;
    for (std::size_t b = 0; b < kBehaviours; ++b) time[b] += in_zone[b] ? dt[i] : 0.0;
  }
  const auto best = std::max_element(time.begin(), time.end());
  if (*best <= 0.0) return std::nullopt;
  return static_cast<sim::RobotBehaviour>(best - time.begin());
}

}  // namespace

void BehaviourBreakdown(const RunTrace& run, const std::vector<double>& dt, bool success,
                        const MetricsConfig& config, SocialStats* out) {
  std::array<std::set<int>, kBehaviours> people;
  std::size_t k = 0;
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    const core::Vec2 p = run.samples[i].X_WR.translation();
    std::array<double, kBehaviours> nearest;
    nearest.fill(std::numeric_limits<double>::infinity());
    for (; k < run.nearby.size() && run.nearby[k].sample == static_cast<int>(i); ++k) {
      const NearbyPedestrian& n = run.nearby[k];
      const auto b = static_cast<std::size_t>(n.behaviour);
      people[b].insert(n.id);
      nearest[b] = std::min(nearest[b], (n.position - p).norm() - n.radius - run.robot_radius);
    }
    for (std::size_t b = 0; b < kBehaviours; ++b) {
      if (!std::isfinite(nearest[b])) continue;
      BehaviourSocial& s = out->by_behaviour[b];
      s.min_gap_m = MinSkipNaN(s.min_gap_m, nearest[b]);
      if (nearest[b] < config.intimate_zone) s.intimate_time_s += dt[i];
      if (nearest[b] < config.personal_zone) s.personal_time_s += dt[i];
    }
  }
  for (std::size_t b = 0; b < kBehaviours; ++b)
    out->by_behaviour[b].people = static_cast<int>(people[b].size());
  if (!success) out->stopped_by = StoppedBy(run, dt, config);
  if (out->stopped_by) ++out->by_behaviour[static_cast<std::size_t>(*out->stopped_by)].runs_stopped;
}

void AddBehaviours(const SocialStats& run, double runs, SocialStats* a) {
  for (std::size_t b = 0; b < kBehaviours; ++b) {
    const BehaviourSocial& r = run.by_behaviour[b];
    BehaviourSocial& s = a->by_behaviour[b];
    s.people += r.people;
    s.min_gap_m = MinSkipNaN(s.min_gap_m, r.min_gap_m);
    s.intimate_time_s += r.intimate_time_s / runs;
    s.personal_time_s += r.personal_time_s / runs;
    s.crowd.Add(r.crowd);
    s.runs_stopped += r.runs_stopped;
  }
}

}  // namespace retrace::bench::internal
