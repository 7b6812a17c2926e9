#include "bench/engine/run_recorder.hpp"

#include <algorithm>
#include <limits>

#include "bench/engine/snapshot_capture.hpp"
#include "bench/engine/update_score.hpp"

namespace retrace::bench {
namespace {

// The robot's edge to the nearest pedestrian's (m), +inf without pedestrians.
double PedestrianGap(const std::vector<sim::DynamicCircle>& people, const core::Vec2& p_W,
                     double radius) {
  double gap = std::numeric_limits<double>::infinity();
  for (const sim::DynamicCircle& c : people) {
    gap = std::min(gap, (c.center - p_W).norm() - c.radius - radius);
  }
  return gap;
}

// The pedestrians whose edge lies within NearbyPedestrian::kNearbyRange of the robot's, with
// their velocities, desired speeds and whether they stand by design, as of sample `sample`.
void RecordNearby(const sim::Simulator& simulator, const std::vector<sim::DynamicCircle>& people,
                  const core::Vec2& p_W, double radius, int sample,
                  std::vector<NearbyPedestrian>* out) {
  const std::vector<sim::PedestrianStatus>& status = simulator.pedestrians().status();
  for (const sim::DynamicCircle& c : people) {
    if ((c.center - p_W).norm() - c.radius - radius > NearbyPedestrian::kNearbyRange) continue;
    NearbyPedestrian n;
    n.sample = sample;
    n.id = c.id;
    n.position = c.center;
    n.velocity = simulator.PedestrianVelocity(c.id);
    n.radius = c.radius;
    const auto it = std::find_if(status.begin(), status.end(),
                                 [&](const sim::PedestrianStatus& st) { return st.id == c.id; });
    n.desired_speed = it != status.end() ? it->desired_speed : 0.0;
    n.standing = it != status.end() && it->standing;
    if (it != status.end()) {
      n.behaviour = it->behaviour;
      n.reacting = it->reacting;
    }
    out->push_back(n);
  }
}

}  // namespace

RunRecorder::RunRecorder(int run, std::uint64_t seed, const TeachTrace& teach,
                         const MetricsConfig& metrics, double robot_radius)
    : metrics_(metrics),
      robot_radius_(robot_radius),
      local_truth_(teach, metrics.match_window, metrics.match_fallback_distance) {
  trace_.run = run;
  trace_.seed = seed;
  trace_.robot_radius = robot_radius;
}

void RunRecorder::OnUpdate(const nav::Localizer& localizer, const nav::LocalizerUpdate& update,
                           const sim::LidarReading& lidar, double t, double cpu_s,
                           std::size_t map_index, const sim::Simulator& simulator) {
  trace_.updates.push_back(ScoreUpdate(update, t, cpu_s, lidar.truth));
  const int crowd = PedestrianBeams(update, lidar);
  if (crowd > 0 && (!trace_.snapshot || crowd > trace_.snapshot->pedestrian_beams)) {
    const core::Pose2 X_WR = simulator.RobotPose();
    trace_.snapshot =
        CaptureSnapshot(localizer, update, lidar, t, static_cast<int>(map_index), X_WR,
                        local_truth_.InMap(X_WR), simulator.PedestrianCircles());
  }
}

void RunRecorder::OnSwitch(double t, const MapChange& map_switch, const core::Pose2& X_WR) {
  trace_.switches.push_back({t, static_cast<int>(map_switch.from), static_cast<int>(map_switch.to),
                             X_WR, map_switch.X_MnR});
  local_truth_.Enter(map_switch.to);
}

core::Pose2 RunRecorder::OnControlTick(double t, std::size_t map_index, const core::Pose2& X_WR,
                                       const core::Pose2& X_MR, bool lost, bool off_map,
                                       const DriveCommand& command,
                                       const sim::Simulator& simulator) {
  PlaybackSample sample;
  sample.time = t;
  sample.map_index = static_cast<int>(map_index);
  sample.X_WR = X_WR;
  sample.X_MR = X_MR;
  sample.X_OR = simulator.OdometryPose();
  sample.command = command.command;
  sample.clearance = simulator.StaticClearance(X_WR.translation()) - robot_radius_;
  // The pedestrians' circles, copied once per tick for both the gap and the nearby list.
  const std::vector<sim::DynamicCircle> people = simulator.PedestrianCircles();
  sample.pedestrian_gap = PedestrianGap(people, X_WR.translation(), robot_radius_);
  sample.avoiding = command.modified;
  sample.lost = lost;
  sample.off_map = off_map;
  if (sample.pedestrian_gap <= NearbyPedestrian::kNearbyRange) {
    RecordNearby(simulator, people, X_WR.translation(), robot_radius_,
                 static_cast<int>(trace_.samples.size()), &trace_.nearby);
  }
  trace_.samples.push_back(sample);
  return local_truth_.InMap(X_WR);
}

void RunRecorder::OnEvents(double t, const std::vector<std::string>& names) {
  for (const std::string& name : names) trace_.events.push_back({t, name});
}

RunTrace RunRecorder::Finish(Outcome outcome, const std::vector<sim::CollisionEvent>& collisions,
                             double sim_time_s, double cpu_time_s) {
  trace_.outcome = outcome;
  trace_.collisions = collisions;
  trace_.sim_time_s = sim_time_s;
  trace_.cpu_time_s = cpu_time_s;
  return std::move(trace_);
}

}  // namespace retrace::bench
