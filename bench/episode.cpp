#include "bench/episode.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "bench/local_truth.hpp"
#include "bench/scripted_events.hpp"
#include "bench/snapshot.hpp"
#include "core/angle.hpp"
#include "core/rng.hpp"
#include "nav/localizer.hpp"
#include "nav/map_server.hpp"
#include "nav/obstacle_avoidance.hpp"
#include "nav/path_follower.hpp"
#include "sim/simulator.hpp"

namespace retrace::bench {
namespace {

constexpr double kProgressPeriod = 10.0;  // s of simulated time between progress reports
constexpr double kStallProgress = 0.5;    // m along the path that counts as progress

// The robot's edge to the nearest pedestrian's (m), +inf without pedestrians.
double PedestrianGap(const sim::Simulator& simulator, const core::Vec2& p_W, double radius) {
  double gap = std::numeric_limits<double>::infinity();
  for (const sim::DynamicCircle& c : simulator.PedestrianCircles()) {
    gap = std::min(gap, (c.center - p_W).norm() - c.radius - radius);
  }
  return gap;
}

// Scores the localizer's dynamic-point mask against which beams really hit a pedestrian.
LocalizerSample Score(const nav::LocalizerUpdate& update, const sim::LidarReading& reading, double time,
                      double cpu_s) {
  LocalizerSample sample;
  sample.time = time;
  sample.cpu_s = cpu_s;
  sample.beams_tested = update.beams_tested;
  sample.beams_rejected = update.beams_rejected;
  for (std::size_t i = 0; i < update.beams.size(); ++i) {
    if (update.beams[i] == nav::BeamUse::kUnused) continue;
    const bool rejected = update.beams[i] == nav::BeamUse::kRejected;
    const bool pedestrian = reading.truth[i].source == sim::BeamSource::kPedestrian;
    if (rejected && pedestrian) ++sample.true_positive;
    if (rejected && !pedestrian) ++sample.false_positive;
    if (!rejected && pedestrian) ++sample.false_negative;
  }
  return sample;
}

}  // namespace

core::Rng PlaybackRng(const ScenarioConfig& config, int run) {
  return core::Rng(config.seed).Split("playback").Split(static_cast<std::uint64_t>(run));
}

RunTrace RunPlayback(const Scenario& scenario, const nav::TeachBundle& bundle, const TeachTrace& teach,
                     int run, double timeout_s, const ProgressFn& progress, PlaybackObserver* observer) {
  const double cpu_start = ThreadCpuSeconds();
  const ScenarioConfig& config = scenario.config;
  const NavConfig& nav_config = config.nav;
  core::Rng rng = PlaybackRng(config, run);
  RunTrace trace;
  trace.run = run;
  trace.seed = rng.seed();

  // The robot starts near the teaching start; the localizer believes it is at map 0's origin.
  core::Rng start_rng = rng.Split("start");
  const double yaw_sigma = core::DegToRad(config.playback.start_offset_yaw_deg);
  const core::Pose2 X_start_offset(config.playback.start_offset_xy * start_rng.Normal(),
                                   config.playback.start_offset_xy * start_rng.Normal(),
                                   yaw_sigma * start_rng.Normal());
  sim::Simulator simulator(scenario.playback_world, config.sim, scenario.X_W_start * X_start_offset,
                           rng.Split("sim"));
  ScriptedEvents events(config.events, EventPhase::kPlayback);
  RouteProgress route_progress(scenario.route);

  nav::Localizer localizer(nav_config.localizer, rng.Split("localizer"));
  nav::PathFollower follower(nav_config.follower);
  nav::ObstacleAvoidance avoidance(nav_config.avoidance);
  nav::MapServer server(bundle);
  server.Start(localizer, follower);
  localizer.Initialize(core::Pose2::Identity(), config.playback.initial_sigma_xy,
                       core::DegToRad(config.playback.initial_sigma_yaw_deg));

  // Ground truth in the current map, for the `lost` check (the metrics recompute it).
  std::optional<LocalTruth> local_truth;
  local_truth.emplace(teach.maps.at(0), config.metrics.match_window, config.metrics.match_fallback_distance);

  const std::uint64_t control_steps =
      sim::PeriodInSteps("nav.control_rate_hz", nav_config.control_rate_hz, simulator.time_step());
  const double control_dt = static_cast<double>(control_steps) * simulator.time_step();
  const double radius = config.sim.robot.radius;
  std::optional<core::LaserScan> latest_scan;
  // Kept for an observer only (the video); the run never reads them.
  std::optional<sim::LidarReading> observed_lidar;
  std::optional<nav::LocalizerUpdate> observed_update;
  double last_switch_time = -std::numeric_limits<double>::infinity();
  core::Twist command;
  double lost_since = -1.0;
  // Progress for the stall check: the maps passed and the path length left in the current one.
  std::pair<std::size_t, double> best_progress{0, std::numeric_limits<double>::infinity()};
  double last_progress_time = 0.0;
  double next_report = kProgressPeriod;
  std::optional<Outcome> outcome;

  for (std::uint64_t step = 1; !outcome; ++step) {
    // 1. Physics, then the sensors that came due.
    const sim::SimStep s = simulator.Step(command);
    const double t = s.time;
    trace.collisions.insert(trace.collisions.end(), s.collisions.begin(), s.collisions.end());

    // 2. Localizer: prediction from each odometry increment, correction from each scan.
    if (s.odometry) localizer.Predict(*s.odometry);
    if (s.lidar) {
      const double cpu0 = ThreadCpuSeconds();
      const nav::LocalizerUpdate update = localizer.Update(s.lidar->scan);
      if (update.ran) {
        trace.updates.push_back(Score(update, *s.lidar, t, ThreadCpuSeconds() - cpu0));
        const int crowd = PedestrianBeams(update, *s.lidar);
        if (crowd > 0 && (!trace.snapshot || crowd > trace.snapshot->pedestrian_beams)) {
          const core::Pose2 X_WR = simulator.RobotPose();
          trace.snapshot = CaptureSnapshot(localizer, update, *s.lidar, t, static_cast<int>(server.index()), X_WR,
                                           local_truth->InMap(X_WR), simulator.PedestrianCircles());
        }
      }
      latest_scan = s.lidar->scan;
      if (observer) {
        observed_lidar = *s.lidar;
        if (update.ran) observed_update = update;
      }
    }

    if (step % control_steps != 0) continue;
    const core::Pose2 X_WR = simulator.RobotPose();

    // 3. Map server: at the end of path k, switch to map k+1 and transform the pose (eq. 1).
    nav::FollowerOutput follow = follower.Compute(localizer.Estimate(), control_dt);
    if (server.SwitchDue(follow)) {
      const nav::MapSwitch sw = server.SwitchToNext(localizer, follower);
      trace.switches.push_back({t, static_cast<int>(sw.from), static_cast<int>(sw.to), X_WR, sw.X_MnR});
      local_truth.emplace(teach.maps.at(sw.to), config.metrics.match_window, config.metrics.match_fallback_distance);
      follow = follower.Compute(localizer.Estimate(), control_dt);
      last_switch_time = t;
    }
    const core::Pose2 X_MR = localizer.Estimate();

    // 4. Follower, then obstacle avoidance on the latest scan, then the robot's command.
    nav::AvoidanceOutput avoid;
    avoid.command = follow.command;
    if (latest_scan) avoid = avoidance.Filter(follow.command, *latest_scan);
    command = avoid.command;

    PlaybackSample sample;
    sample.time = t;
    sample.map_index = static_cast<int>(server.index());
    sample.X_WR = X_WR;
    sample.X_MR = X_MR;
    sample.X_OR = simulator.OdometryPose();
    sample.command = command;
    sample.clearance = simulator.StaticClearance(X_WR.translation()) - radius;
    sample.pedestrian_gap = PedestrianGap(simulator, X_WR.translation(), radius);
    sample.avoiding = avoid.modified;
    trace.samples.push_back(sample);

    const core::Pose2 X_MR_truth = local_truth->InMap(X_WR);
    if (observer) {
      const std::vector<sim::DynamicCircle> pedestrians = simulator.PedestrianCircles();
      observer->OnTick({t, localizer, server, X_WR, X_MR_truth, command.v,
                        t - last_switch_time, observed_lidar ? &*observed_lidar : nullptr,
                        observed_update ? &*observed_update : nullptr, pedestrians});
    }

    // 5. Scripted events and the end conditions.
    for (const std::string& name : events.Fire(t, route_progress.Update(X_WR.translation()), simulator)) {
      trace.events.push_back({t, name});
    }
    const double error = Compare(X_MR, X_MR_truth).distance;
    if (error > config.limits.lost_distance) {
      if (lost_since < 0.0) lost_since = t;
    } else {
      lost_since = -1.0;
    }
    if (server.index() > best_progress.first || follow.remaining < best_progress.second - kStallProgress) {
      best_progress = {server.index(), follow.remaining};
      last_progress_time = t;
    }
    if (follow.goal_reached && server.IsLast()) {
      outcome = Outcome::kSuccess;
    } else if (config.limits.stop_on_collision && !trace.collisions.empty()) {
      outcome = Outcome::kCollision;
    } else if (lost_since >= 0.0 && t - lost_since >= config.limits.lost_time) {
      outcome = Outcome::kLost;
    } else if (t >= timeout_s || t - last_progress_time >= config.limits.stall_time) {
      outcome = Outcome::kTimeout;
    }
    if (progress && t >= next_report) {
      progress(t);
      next_report += kProgressPeriod;
    }
  }
  if (observer) observer->OnEnd();
  trace.outcome = *outcome;
  trace.sim_time_s = simulator.time();
  trace.cpu_time_s = ThreadCpuSeconds() - cpu_start;
  return trace;
}

}  // namespace retrace::bench
