#include "bench/metrics/internal/collisions.hpp"

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "bench/metrics/internal/sample_stats.hpp"

namespace retrace::bench::internal {
namespace {

using core::Vec2;

// The speed (m/s) at which the robot moved towards `point_W` just before `time`: its
// ground-truth displacement over the last `window` s of samples up to `time`, projected on the
// direction from its centre to the point. 0 without two such samples.
double SpeedTowards(const std::vector<PlaybackSample>& samples, double time, Vec2 point_W,
                    double window) {
  const auto after = std::upper_bound(samples.begin(), samples.end(), time,
                                      [](double t, const PlaybackSample& s) { return t < s.time; });
  if (after == samples.begin()) return 0.0;
  const PlaybackSample& now = *(after - 1);
  auto from = std::lower_bound(samples.begin(), after - 1, now.time - window,
                               [](const PlaybackSample& s, double t) { return s.time < t; });
  if (from == after - 1 || now.time <= from->time) return 0.0;
  const Vec2 velocity =
      (now.X_WR.translation() - from->X_WR.translation()) / (now.time - from->time);
  const Vec2 towards = point_W - now.X_WR.translation();
  const double distance = towards.norm();
  return distance > 1e-9 ? velocity.dot(towards) / distance : 0.0;
}

}  // namespace

CollisionStats Collisions(const RunTrace& run, const MetricsConfig& config) {
  CollisionStats out;
  std::vector<sim::CollisionEvent> events = run.collisions;
  std::stable_sort(events.begin(), events.end(),
                   [](const auto& a, const auto& b) { return a.time < b.time; });
  std::map<std::pair<int, int>, double> last_contact;  // (kind, pedestrian id) -> time
  for (const sim::CollisionEvent& e : events) {
    const bool pedestrian = e.kind == sim::CollisionKind::kPedestrian;
    const std::pair<int, int> key{pedestrian ? 1 : 0, pedestrian ? e.pedestrian_id : -1};
    const auto it = last_contact.find(key);
    const bool new_incident =
        it == last_contact.end() || !(e.time - it->second < config.collision_merge_time);
    (pedestrian ? out.pedestrian_events : out.static_events) += 1;
    if (new_incident) (pedestrian ? out.pedestrian_incidents : out.static_incidents) += 1;
    if (new_incident && pedestrian &&
        SpeedTowards(run.samples, e.time, e.point_W, config.collision_speed_window) >
            config.collision_driving_speed) {
      ++out.pedestrian_incidents_robot_driving;
    }
    last_contact[key] = e.time;
  }
  for (const PlaybackSample& s : run.samples) {
    out.min_clearance_m = MinSkipNaN(out.min_clearance_m, s.clearance);
    out.min_pedestrian_gap_m = MinSkipNaN(out.min_pedestrian_gap_m, s.pedestrian_gap);
  }
  return out;
}

}  // namespace retrace::bench::internal
