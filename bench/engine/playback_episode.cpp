#include "bench/engine/playback_episode.hpp"

#include <limits>
#include <utility>
#include <vector>

#include "bench/engine/end_conditions.hpp"
#include "bench/engine/local_truth.hpp"
#include "bench/engine/playback.hpp"
#include "bench/engine/run_recorder.hpp"
#include "bench/engine/scripted_events.hpp"
#include "bench/engine/stack_insight.hpp"
#include "bench/engine/stack_progress.hpp"
#include "bench/engine/stepper.hpp"
#include "bench/engine/thread_cpu_time.hpp"
#include "core/angle.hpp"
#include "core/check.hpp"
#include "core/rng.hpp"
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

}  // namespace

// The episode's parts (named, not anonymous: PlaybackEpisode::State holds them).
namespace playback_parts {

// What an observer (the video) sees besides the loop's own state: the latest scan and update.
// Only a stack that lets the harness look inside (StackInsight) can be watched.
class ObserverFeed {
 public:
  ObserverFeed(PlaybackObserver* observer, const NavigationStack& stack)
      : observer_(stack.insight() != nullptr ? observer : nullptr), insight_(stack.insight()) {}
  void OnScan(const sim::LidarReading& lidar, const nav::LocalizerUpdate* update) {
    if (!observer_) return;
    lidar_ = lidar;
    if (update != nullptr && update->ran) update_ = *update;
  }
  void OnSwitch(double t) { last_switch_ = t; }
  void OnTick(double t, const core::Pose2& X_WR, const core::Pose2& X_MR_truth, double speed,
              const sim::Simulator& simulator) {
    if (!observer_) return;
    const std::vector<sim::DynamicCircle> pedestrians = simulator.PedestrianCircles();
    observer_->OnTick({t, insight_->localizer(), insight_->server(), X_WR, X_MR_truth, speed,
                       t - last_switch_, lidar_ ? &*lidar_ : nullptr, update_ ? &*update_ : nullptr,
                       pedestrians});
  }
  void OnEnd() {
    if (observer_) observer_->OnEnd();
  }

 private:
  PlaybackObserver* observer_;
  const StackInsight* insight_;
  std::optional<sim::LidarReading> lidar_;
  std::optional<nav::LocalizerUpdate> update_;
  double last_switch_ = -std::numeric_limits<double>::infinity();
};

// A scripted takeover (EventAction::kTakeover): from the tick its event fires, an operator drives
// the robot from where it is through the event's points, as the teacher drives a route; its
// command replaces the stack's. When it hands the robot back, the stack resumes by place
// (NavigationStack::Resume).
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

  // While driving: the operator's command into out->drive (nothing of the stack's is applied);
  // returns the stack's switch when the robot is handed back into another map.
  std::optional<MapChange> Drive(const core::Pose2& X_WR, double dt, NavigationStack& stack,
                                 StackOutput* out) {
    if (!driver_) return std::nullopt;
    out->drive = {.command = driver_->Command(X_WR, dt)};
    if (!driver_->Done()) return std::nullopt;
    driver_.reset();
    return stack.Resume(out);
  }

 private:
  sim::TeacherConfig teacher_;
  core::Rng rng_;
  std::optional<sim::Teacher> driver_;
};

}  // namespace playback_parts

struct PlaybackEpisode::State {
  State(const Scenario& scenario, const nav::TeachBundle& bundle, const TeachTrace& teach,
        int run, double timeout_s, NavigationStack& nav_stack, const ProgressFn& progress,
        PlaybackObserver* observer, SensorTap* sensor_tap)
      : cpu_start(ThreadCpuSeconds()),
        config(scenario.config),
        rng(PlaybackRng(config, run)),
        simulator(scenario.playback_world, config.sim, StartPose(scenario, rng.Split("start")),
                  rng.Split("sim")),
        stepper(simulator, config.nav.control_rate_hz, progress),
        events(config.events, EventPhase::kPlayback),
        route_progress(scenario.route),
        stack(nav_stack),
        stack_progress(bundle),
        recorder(run, rng.seed(), teach, config.metrics, scenario.robot.radius),
        end(config.limits, timeout_s),
        feed(observer, nav_stack),
        takeover(config.teach.teacher, rng.Split("operator")),
        tap(sensor_tap),
        goal(teach.X_WR.empty() ? std::nullopt : std::optional(teach.X_WR.back().translation())) {
    stepper.SetTap(tap);
  }

  double cpu_start;
  const ScenarioConfig& config;
  core::Rng rng;
  sim::Simulator simulator;
  Stepper stepper;
  ScriptedEvents events;
  RouteProgress route_progress;
  NavigationStack& stack;
  StackProgress stack_progress;
  RunRecorder recorder;
  EndConditions end;
  playback_parts::ObserverFeed feed;
  playback_parts::OperatorTakeover takeover;
  SensorTap* tap;
  std::optional<core::Vec2> goal;  // the taught route's end, W (none: no teach trace)
  core::Twist command;
  double time = 0.0;
  bool sensed = false;
  std::size_t map = 0;  // the stack's map at its last answer
  std::optional<Outcome> outcome;
};

PlaybackEpisode::PlaybackEpisode(const Scenario& scenario, const nav::TeachBundle& bundle,
                                 const TeachTrace& teach, int run, double timeout_s,
                                 NavigationStack& stack, const ProgressFn& progress,
                                 PlaybackObserver* observer, SensorTap* tap)
    : state_(std::make_unique<State>(scenario, bundle, teach, run, timeout_s, stack, progress,
                                     observer, tap)) {}

PlaybackEpisode::~PlaybackEpisode() = default;

bool PlaybackEpisode::done() const { return state_->outcome.has_value(); }
double PlaybackEpisode::time() const { return state_->time; }

void PlaybackEpisode::Sense() {
  State& s = *state_;
  RETRACE_CHECK(!s.outcome);
  do {
    // 1. Step the world; the sensors that came due.
    const sim::SimStep step = s.stepper.Step(s.command);
    s.time = step.time;
    // 2. Localize: each odometry increment, each scan (an update that ran is scored).
    if (step.odometry) s.stack.OnOdometry(step.time, *step.odometry);
    if (!step.lidar) continue;
    const double cpu0 = ThreadCpuSeconds();
    s.stack.OnScan(step.lidar->scan);
    const StackInsight* insight = s.stack.insight();
    const nav::LocalizerUpdate* update = insight ? insight->last_update() : nullptr;
    if (update != nullptr && update->ran) {
      s.recorder.OnUpdate(insight->localizer(), *update, *step.lidar, step.time,
                          ThreadCpuSeconds() - cpu0, insight->server().index(), s.simulator);
    }
    s.feed.OnScan(*step.lidar, update);
  } while (!s.stepper.ControlDue());
  s.sensed = true;
}

bool PlaybackEpisode::Act() {
  State& s = *state_;
  RETRACE_CHECK(s.sensed && !s.outcome);
  s.sensed = false;
  const double t = s.time;
  const double dt = s.stepper.control_dt();
  const core::Pose2 X_WR = s.simulator.RobotPose();
  // 3. The stack's answer: follow the taught path, switch maps, avoid.
  StackOutput out = s.stack.OnControlTick(t, dt);
  const auto record_switch = [&](const MapChange& sw) {
    s.recorder.OnSwitch(t, sw, X_WR);
    s.feed.OnSwitch(t);
  };
  if (out.map_change) record_switch(*out.map_change);
  // 4. Command the robot (an operator who took it over drives it).
  if (const auto sw = s.takeover.Drive(X_WR, dt, s.stack, &out)) record_switch(*sw);
  s.command = out.drive.command;
  s.map = out.map;
  // 5. Record; scripted events; check the end.
  const core::Pose2 X_MR_truth =
      s.recorder.OnControlTick(t, out.map, X_WR, out.X_MR, out.lost, out.off_map, out.drive,
                               s.simulator);
  s.feed.OnTick(t, X_WR, X_MR_truth, s.command.v, s.simulator);
  s.recorder.OnEvents(t,
                      s.events.Fire(t, s.route_progress.Update(X_WR.translation()), s.simulator));
  if (std::vector<core::Vec2> drive = s.events.TakeOver(); !drive.empty()) {
    s.takeover.Begin(std::move(drive), X_WR.translation());
  }
  // The stack's progress along its map's taught path, as the harness sees it.
  const double remaining = s.stack_progress.Remaining(out.map, out.X_MR);
  s.outcome = s.end.Check({t, out.route_done && !s.takeover.driving(),
                           s.stack_progress.IsLast(out.map), !s.stepper.collisions().empty(),
                           Compare(out.X_MR, X_MR_truth).distance,
                           s.goal ? (X_WR.translation() - *s.goal).norm() : 0.0, out.map,
                           remaining, s.takeover.driving()});
  return s.outcome.has_value();
}

const PlaybackSample* PlaybackEpisode::last_sample() const {
  const std::vector<PlaybackSample>& samples = state_->recorder.trace().samples;
  return samples.empty() ? nullptr : &samples.back();
}

std::size_t PlaybackEpisode::collisions() const { return state_->stepper.collisions().size(); }

RunTrace PlaybackEpisode::Finish() {
  State& s = *state_;
  RETRACE_CHECK(s.outcome);
  s.feed.OnEnd();
  if (s.tap != nullptr) s.tap->OnEnd();
  return s.recorder.Finish(*s.outcome, s.stepper.collisions(), s.simulator.time(),
                           ThreadCpuSeconds() - s.cpu_start);
}

}  // namespace retrace::bench
