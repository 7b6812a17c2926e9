#include "bench/metrics/internal/social.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "bench/metrics/internal/sample_stats.hpp"

namespace retrace::bench::internal {
namespace {

// Each sample holds until the next one; the last one for the median step (a control period).
std::vector<double> SampleDurations(const std::vector<PlaybackSample>& samples) {
  std::vector<double> dt(samples.size(), 0.0);
  for (std::size_t i = 0; i + 1 < samples.size(); ++i) {
    dt[i] = std::max(0.0, samples[i + 1].time - samples[i].time);
  }
  if (samples.size() >= 2) {
    std::vector<double> steps(dt.begin(), dt.end() - 1);
    std::nth_element(steps.begin(), steps.begin() + static_cast<long>(steps.size() / 2),
                     steps.end());
    dt.back() = steps[steps.size() / 2];
  }
  return dt;
}

// |j| at the samples' interior, from the ground-truth positions.
std::vector<double> Jerk(const std::vector<PlaybackSample>& samples) {
  const std::size_t n = samples.size();
  std::vector<double> out;
  if (n < 4) return out;
  std::vector<core::Vec2> v(n - 1), a(n - 2);
  std::vector<double> tv(n - 1), ta(n - 2);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double dt = samples[i + 1].time - samples[i].time;
    v[i] =
        dt > 0.0
            ? core::Vec2((samples[i + 1].X_WR.translation() - samples[i].X_WR.translation()) / dt)
            : core::Vec2(kMetricNaN, kMetricNaN);
    tv[i] = 0.5 * (samples[i].time + samples[i + 1].time);
  }
  for (std::size_t i = 0; i + 1 < v.size(); ++i) {
    const double dt = tv[i + 1] - tv[i];
    a[i] = dt > 0.0 ? core::Vec2((v[i + 1] - v[i]) / dt) : core::Vec2(kMetricNaN, kMetricNaN);
    ta[i] = 0.5 * (tv[i] + tv[i + 1]);
  }
  for (std::size_t i = 0; i + 1 < a.size(); ++i) {
    const double dt = ta[i + 1] - ta[i];
    out.push_back(dt > 0.0 ? ((a[i + 1] - a[i]) / dt).norm() : kMetricNaN);
  }
  return out;
}

// An encounter in progress: how long the pedestrian has stood and walked slowly in it, and
// whether it stands by design (then its speed is no reaction to the robot).
struct Encounter {
  double stood_s = 0.0;
  double slow_s = 0.0;
  bool standing = false;
  sim::RobotBehaviour behaviour = sim::RobotBehaviour::kRegular;
};

void CloseInto(const Encounter& e, CrowdReaction* crowd) {
  ++crowd->encounters;
  if (e.standing) {
    ++crowd->standing;
    return;
  }
  if (e.stood_s >= kReactionTime) {
    ++crowd->blocked;
  } else if (e.slow_s >= kReactionTime) {
    ++crowd->yielded;
  } else {
    ++crowd->passed;
  }
  crowd->wait_time_s += e.stood_s;
  crowd->max_wait_s = std::max(crowd->max_wait_s, e.stood_s);
}

// Counts the ended encounter overall and for its person's behaviour.
void Close(const Encounter& e, SocialStats* out) {
  CloseInto(e, &out->crowd);
  CloseInto(e, &out->by_behaviour[static_cast<std::size_t>(e.behaviour)].crowd);
}

}  // namespace

double TimeToCollision(const core::Vec2& dp, const core::Vec2& dv, double reach) {
  const double c = dp.squaredNorm() - reach * reach;
  if (c <= 0.0) return 0.0;  // touching or overlapping now
  const double a = dv.squaredNorm();
  const double b = dp.dot(dv);
  if (!(a > 0.0) || b >= 0.0) return std::numeric_limits<double>::infinity();  // not closing
  const double discriminant = b * b - a * c;
  if (discriminant < 0.0) return std::numeric_limits<double>::infinity();  // passes by
  return (-b - std::sqrt(discriminant)) / a;
}

namespace {

// The encounters of a run (the pedestrians that came within the personal zone, each closed when
// it leaves the zone by the hysteresis or the record) into out->crowd, and the smallest time to
// collision into out->min_ttc_s. dt: the samples' durations (s).
void TrackEncounters(const RunTrace& run, const std::vector<double>& dt,
                     const MetricsConfig& config, SocialStats* out) {
  const std::vector<PlaybackSample>& samples = run.samples;
  if (!samples.empty()) out->min_ttc_s = config.ttc_horizon;
  std::map<int, Encounter> open;  // by pedestrian id
  std::size_t k = 0;              // run.nearby is ordered by sample
  std::vector<int> seen;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const PlaybackSample& s = samples[i];
    const core::Vec2 p = s.X_WR.translation();
    const core::Vec2 v_robot =
        s.command.v * core::Vec2(std::cos(s.X_WR.theta), std::sin(s.X_WR.theta));
    seen.clear();
    for (; k < run.nearby.size() && run.nearby[k].sample == static_cast<int>(i); ++k) {
      const NearbyPedestrian& n = run.nearby[k];
      const double ttc =
          TimeToCollision(n.position - p, n.velocity - v_robot, n.radius + run.robot_radius);
      out->min_ttc_s = std::min(out->min_ttc_s, ttc);

      const double gap = (n.position - p).norm() - n.radius - run.robot_radius;
      auto it = open.find(n.id);
      if (it == open.end() && gap < config.personal_zone) {
        it = open.emplace(n.id, Encounter{}).first;
        it->second.standing = n.standing;
        it->second.behaviour = n.behaviour;
      }
      if (it == open.end()) continue;
      if (gap > config.personal_zone + kEncounterHysteresis) {
        Close(it->second, out);
        open.erase(it);
        continue;
      }
      seen.push_back(n.id);
      const double speed = n.velocity.norm();
      if (speed < kStopSpeed) {
        it->second.stood_s += dt[i];
      } else if (speed < kYieldSpeedFraction * n.desired_speed) {
        it->second.slow_s += dt[i];
      }
    }
    // Pedestrians that left the record (farther than 5 m, or gone) end their encounters.
    for (auto it = open.begin(); it != open.end();) {
      if (std::find(seen.begin(), seen.end(), it->first) == seen.end()) {
        Close(it->second, out);
        it = open.erase(it);
      } else {
        ++it;
      }
    }
  }
  for (const auto& [id, e] : open) Close(e, out);
}

}  // namespace

SocialStats Social(const RunTrace& run, double taught_length_m, double taught_time_s, bool success,
                   double path_length_m, double time_s, const MetricsConfig& config) {
  SocialStats out;
  const std::vector<PlaybackSample>& samples = run.samples;
  const std::vector<double> dt = SampleDurations(samples);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (samples[i].pedestrian_gap < config.intimate_zone) out.intimate_time_s += dt[i];
    if (samples[i].pedestrian_gap < config.personal_zone) out.personal_time_s += dt[i];
  }
  if (success && path_length_m > 0.0) out.path_efficiency = taught_length_m / path_length_m;
  if (success && time_s > 0.0) out.time_efficiency = taught_time_s / time_s;
  out.jerk_m_s3 = Summarize(Jerk(samples));
  TrackEncounters(run, dt, config, &out);
  BehaviourBreakdown(run, dt, success, config, &out);
  return out;
}

SocialStats AggregateSocial(const std::vector<RunMetrics>& runs) {
  SocialStats a;
  if (runs.empty()) return a;
  double path_sum = 0.0, time_sum = 0.0;
  int successes = 0;
  std::vector<const Summary*> jerks;
  for (const RunMetrics& m : runs) {
    const SocialStats& s = m.social;
    a.intimate_time_s += s.intimate_time_s / static_cast<double>(runs.size());
    a.personal_time_s += s.personal_time_s / static_cast<double>(runs.size());
    a.min_ttc_s = MinSkipNaN(a.min_ttc_s, s.min_ttc_s);
    if (std::isfinite(s.path_efficiency) && std::isfinite(s.time_efficiency)) {
      path_sum += s.path_efficiency;
      time_sum += s.time_efficiency;
      ++successes;
    }
    jerks.push_back(&s.jerk_m_s3);
    a.crowd.Add(s.crowd);
    AddBehaviours(s, static_cast<double>(runs.size()), &a);
  }
  if (successes > 0) {
    a.path_efficiency = path_sum / successes;
    a.time_efficiency = time_sum / successes;
  }
  a.jerk_m_s3 = MeanOfSummaries(jerks);
  return a;
}

}  // namespace retrace::bench::internal
