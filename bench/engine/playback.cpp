#include "bench/engine/playback.hpp"

#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "bench/engine/end_conditions.hpp"
#include "bench/engine/local_truth.hpp"
#include "bench/engine/run_recorder.hpp"
#include "bench/engine/scripted_events.hpp"
#include "bench/engine/stepper.hpp"
#include "bench/engine/thread_cpu_time.hpp"
#include "core/angle.hpp"
#include "core/rng.hpp"
#include "nav/navigator.hpp"
#include "nav/obstacle_avoidance.hpp"
#include "sim/simulator.hpp"
#include "sim/teacher.hpp"

namespace retrace::bench {
namespace {

// The robot's true start: the teaching start plus a Gaussian offset.
core::Pose2 StartPose(const Scenario& scenario, core::Rng rng) {
  const PlaybackConfig& p = scenario.config.playback;
  const double yaw_sigma = core::DegToRad(p.start_offset_yaw_deg);
  const core::Pose2 X_start_offset(p.start_offset_xy * rng.Normal(),
                                   p.start_offset_xy * rng.Normal(), yaw_sigma * rng.Normal());
  return scenario.X_W_start * X_start_offset;
}

// What an observer (the video) sees besides the loop's own state: the latest scan and update.
class ObserverFeed {
 public:
  explicit ObserverFeed(PlaybackObserver* observer) : observer_(observer) {}
  void OnScan(const sim::LidarReading& lidar, const nav::LocalizerUpdate& update) {
    if (!observer_) return;
    lidar_ = lidar;
    if (update.ran) update_ = update;
  }
  void OnSwitch(double t) { last_switch_ = t; }
  void OnTick(double t, const nav::Localizer& localizer, const nav::MapServer& server,
              const core::Pose2& X_WR, const core::Pose2& X_MR_truth, double speed,
              const sim::Simulator& simulator) {
    if (!observer_) return;
    const std::vector<sim::DynamicCircle> pedestrians = simulator.PedestrianCircles();
    observer_->OnTick({t, localizer, server, X_WR, X_MR_truth, speed, t - last_switch_,
                       lidar_ ? &*lidar_ : nullptr, update_ ? &*update_ : nullptr, pedestrians});
  }
  void OnEnd() {
    if (observer_) observer_->OnEnd();
  }

 private:
  PlaybackObserver* observer_;
  std::optional<sim::LidarReading> lidar_;
  std::optional<nav::LocalizerUpdate> update_;
  double last_switch_ = -std::numeric_limits<double>::infinity();
};

// The navigation stack at the start of a run: it believes the robot is at map 0's origin.
nav::Navigator StartNavigator(const Scenario& scenario, const nav::TeachBundle& bundle,
                              const core::Rng& rng) {
  const ScenarioConfig& config = scenario.config;
  nav::MapServerConfig server;
  server.closure_radius = config.route.revisit_radius;
  server.drift = config.route.online_drift;
  nav::Navigator nav(config.nav.localizer, config.nav.follower, scenario.robot, bundle, server,
                     rng.Split("localizer"));
  nav.Start(0, core::Pose2::Identity(), config.playback.initial_sigma_xy,
            core::DegToRad(config.playback.initial_sigma_yaw_deg));
  return nav;
}

// Step 2 of the loop: predict from the odometry increment, update with the scan (scored), and
// keep the scan for avoidance.
void Localize(const sim::SimStep& s, const sim::Simulator& simulator, nav::Navigator& nav,
              RunRecorder& recorder, ObserverFeed& feed, std::optional<core::LaserScan>* latest) {
  if (s.odometry) nav.OnOdometry(*s.odometry);
  if (!s.lidar) return;
  const double cpu0 = ThreadCpuSeconds();
  const nav::LocalizerUpdate update = nav.OnScan(s.lidar->scan);
  if (update.ran) {
    recorder.OnUpdate(nav.localizer(), update, *s.lidar, s.time, ThreadCpuSeconds() - cpu0,
                      nav.server().index(), simulator);
  }
  *latest = s.lidar->scan;
  feed.OnScan(*s.lidar, update);
}

// A map switch (or a takeover's hand-back into another map) goes to the run and the observer.
void RecordSwitch(double time, const nav::MapSwitch& sw, const core::Pose2& X_WR,
                  RunRecorder& recorder, ObserverFeed& feed) {
  recorder.OnSwitch(time, sw, X_WR);
  feed.OnSwitch(time);
}

// A scripted takeover (EventAction::kTakeover): from the tick its event fires, an operator drives
// the robot from where it is through the event's points, as the teacher drives a route; its
// command replaces the navigator's. When it hands the robot back, the navigator resumes by place
// (nav::Navigator::Resume).
class OperatorTakeover {
 public:
  OperatorTakeover(const sim::TeacherConfig& teacher, core::Rng rng)
      : teacher_(teacher), rng_(rng) {}

  bool driving() const { return driver_.has_value(); }

  // A takeover event fired (its points, W) with the robot at p_W.
  void Begin(std::vector<core::Vec2> drive, const core::Vec2& p_W) {
    drive.insert(drive.begin(), p_W);
    driver_.emplace(std::move(drive), teacher_, rng_);
  }

  // While driving: the operator's command into *avoid (nothing of the navigator's is applied);
  // returns the navigator's switch when the robot is handed back into another map.
  std::optional<nav::MapSwitch> Drive(const core::Pose2& X_WR, double dt, nav::Navigator& nav,
                                      nav::AvoidanceOutput* avoid) {
    if (!driver_) return std::nullopt;
    *avoid = {.command = driver_->Command(X_WR, dt)};
    if (!driver_->Done()) return std::nullopt;
    driver_.reset();
    return nav.Resume();
  }

 private:
  sim::TeacherConfig teacher_;
  core::Rng rng_;
  std::optional<sim::Teacher> driver_;
};

}  // namespace

core::Rng PlaybackRng(const ScenarioConfig& config, int run) {
  return core::Rng(config.seed).Split("playback").Split(static_cast<std::uint64_t>(run));
}

RunTrace RunPlayback(const Scenario& scenario, const nav::TeachBundle& bundle,
                     const TeachTrace& teach, int run, double timeout_s, const ProgressFn& progress,
                     PlaybackObserver* observer, SensorTap* tap) {
  const double cpu_start = ThreadCpuSeconds();
  const ScenarioConfig& config = scenario.config;
  const core::Rng rng = PlaybackRng(config, run);
  sim::Simulator simulator(scenario.playback_world, config.sim,
                           StartPose(scenario, rng.Split("start")), rng.Split("sim"));
  Stepper stepper(simulator, config.nav.control_rate_hz, progress);
  stepper.SetTap(tap);
  ScriptedEvents events(config.events, EventPhase::kPlayback);
  RouteProgress route_progress(scenario.route);
  nav::Navigator nav = StartNavigator(scenario, bundle, rng);
  nav::ObstacleAvoidance avoidance(config.nav.avoidance, scenario.robot);
  RunRecorder recorder(run, rng.seed(), teach, config.metrics, scenario.robot.radius);
  EndConditions end(config.limits, timeout_s);
  ObserverFeed feed(observer);
  std::optional<core::LaserScan> latest_scan;
  core::Twist command;
  std::optional<Outcome> outcome;
  OperatorTakeover takeover(config.teach.teacher, rng.Split("operator"));

  while (!outcome) {
    // 1. Step the world; the sensors that came due.
    const sim::SimStep s = stepper.Step(command);
    // 2. Localize: prediction from each odometry increment, correction from each scan.
    Localize(s, simulator, nav, recorder, feed, &latest_scan);
    if (!stepper.ControlDue()) continue;
    const core::Pose2 X_WR = simulator.RobotPose();
    // 3. Follow the taught path; at its end, map k+1 and the pose carried over by eq. (1).
    const nav::NavigatorTick tick = nav.OnControlTick(stepper.control_dt());
    if (tick.map_switch) RecordSwitch(s.time, *tick.map_switch, X_WR, recorder, feed);
    // 4. Avoid on the latest scan, command the robot (an operator who took it over drives it).
    nav::AvoidanceOutput avoid{.command = tick.follow.command};
    if (latest_scan) avoid = avoidance.Filter(tick.follow.command, *latest_scan);
    if (const auto sw = takeover.Drive(X_WR, stepper.control_dt(), nav, &avoid)) {
      RecordSwitch(s.time, *sw, X_WR, recorder, feed);
    }
    command = avoid.command;
    // 5. Record; scripted events; check the end.
    const core::Pose2 X_MR = nav.Estimate();
    const core::Pose2 X_MR_truth = recorder.OnControlTick(
        s.time, nav.server().index(), X_WR, X_MR, nav.localizer().lost(), avoid, simulator);
    feed.OnTick(s.time, nav.localizer(), nav.server(), X_WR, X_MR_truth, command.v, simulator);
    recorder.OnEvents(s.time,
                      events.Fire(s.time, route_progress.Update(X_WR.translation()), simulator));
    if (std::vector<core::Vec2> drive = events.TakeOver(); !drive.empty()) {
      takeover.Begin(std::move(drive), X_WR.translation());
    }
    outcome = end.Check({s.time, tick.route_done && !takeover.driving(), nav.server().IsLast(),
                         !stepper.collisions().empty(), Compare(X_MR, X_MR_truth).distance,
                         nav.server().index(), tick.follow.remaining, takeover.driving()});
  }
  feed.OnEnd();
  if (tap != nullptr) tap->OnEnd();
  return recorder.Finish(*outcome, stepper.collisions(), simulator.time(),
                         ThreadCpuSeconds() - cpu_start);
}

}  // namespace retrace::bench
