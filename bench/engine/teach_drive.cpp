#include "bench/engine/teach_drive.hpp"

#include "nav/route_graph.hpp"

#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "bench/engine/scripted_events.hpp"
#include "bench/engine/stepper.hpp"
#include "bench/engine/thread_cpu_time.hpp"
#include "core/check.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "nav/route_graph.hpp"
#include "nav/teach_recorder.hpp"
#include "sim/simulator.hpp"
#include "sim/teacher.hpp"

namespace retrace::bench {

namespace {

// Splits the poses a finished recorder was given into its `map_count` maps.
std::vector<TeachMapTrace> MapTraces(const nav::TeachRecorder& recorder, std::size_t map_count,
                                     const std::vector<double>& time,
                                     const std::vector<core::Pose2>& X_WR) {
  const std::vector<nav::RecordedPose>& poses = recorder.recorded_poses();
  RETRACE_CHECK(poses.size() == time.size());
  RETRACE_CHECK(X_WR.empty() || X_WR.size() == time.size());
  std::vector<TeachMapTrace> maps(map_count);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    TeachMapTrace& map = maps.at(poses[i].map);
    map.time.push_back(time[i]);
    map.X_MR.push_back(poses[i].X_MR);
    if (!X_WR.empty()) map.X_WR.push_back(X_WR[i]);
  }
  return maps;
}

}  // namespace

std::vector<ModeRecorder> MakeModeRecorders(
    const std::vector<MapMode>& modes, const NavConfig& nav, const nav::RobotGeometry& robot,
    const std::optional<nav::OnlineSwitchingConfig>& online) {
  std::vector<ModeRecorder> recorders;
  recorders.reserve(modes.size());
  for (MapMode mode : modes) {
    std::optional<nav::ScanMatcherConfig> matcher;
    if (mode == MapMode::kScanMatched) matcher = nav.scan_matcher;
    recorders.push_back({mode, nav::TeachRecorder(nav.mapper, robot, matcher,
                                                  SwitchesMaps(mode) ? online : std::nullopt)});
  }
  return recorders;
}

void SignalSwitches(std::vector<ModeRecorder>& recorders, const std::vector<double>& switch_points,
                    double progress) {
  for (ModeRecorder& r : recorders) {
    if (!SwitchesMaps(r.mode)) continue;
    while (r.next_switch < switch_points.size() && progress >= switch_points[r.next_switch]) {
      r.recorder.CloseMap();
      ++r.next_switch;
    }
  }
}

std::vector<ModeTeach> FinishModeRecorders(std::vector<ModeRecorder>& recorders,
                                           const TeachTrace& trace, const std::vector<double>& time,
                                           const std::vector<core::Pose2>& X_WR,
                                           const RouteConfig& route) {
  const nav::RouteLinkConfig link = route.Link();
  std::vector<ModeTeach> teaches;
  for (ModeRecorder& r : recorders) {
    ModeTeach m;
    m.mode = r.mode;
    m.bundle = r.recorder.Finish();  // first: it integrates the keyframes held back (online)
    nav::LinkRoute(m.bundle, link);
    m.match_counts = r.recorder.match_counts();
    m.online_switches = r.recorder.online_switches();
    m.trace = trace;
    m.trace.maps = MapTraces(r.recorder, m.bundle.maps.size(), time, X_WR);
    teaches.push_back(std::move(m));
  }
  return teaches;
}

void RequireSwitchingModeIfOnline(const Scenario& scenario, const std::vector<MapMode>& modes) {
  if (!scenario.switching_online()) return;
  for (MapMode mode : modes) {
    if (SwitchesMaps(mode)) return;
  }
  std::string asked;
  for (MapMode mode : modes)
    asked += (asked.empty() ? "" : ", ") + std::string(core::EnumName(mode));
  throw core::ConfigError("route.switch_points",
                          "`online` switching needs a map mode that switches maps (partial or "
                          "scan_matched); the modes asked for are: " +
                              asked);
}

namespace {

core::WorldError TeacherStuck(const Scenario& scenario, double timeout, const core::Pose2& X_WR,
                              const sim::Teacher& teacher) {
  return core::WorldError(scenario.source.string() +
                          ": the teacher did not finish the route within " +
                          core::FormatNumber(timeout) + " s; stuck at (" +
                          core::FormatNumber(X_WR.x) + ", " + core::FormatNumber(X_WR.y) + "), " +
                          core::FormatNumber(teacher.Progress()) + " m along the route");
}

// One call of a teaching drive on its recorders, in the drive's order: the pose of each mode's
// source at an odometry tick, a scan, or the operator's switch signal.
struct RecorderCall {
  enum class Kind { kPose, kScan, kSwitch };
  Kind kind = Kind::kPose;
  core::Pose2 X_OR;   // kPose: the odometry pose
  core::Pose2 X_M0R;  // kPose: ground truth from the start, the consistent map's pose source
  std::shared_ptr<const core::LaserScan> scan;  // kScan
};

void Apply(const RecorderCall& call, ModeRecorder& r) {
  switch (call.kind) {
    case RecorderCall::Kind::kPose:
      r.recorder.OnPose(r.mode == MapMode::kConsistent ? call.X_M0R : call.X_OR);
      break;
    case RecorderCall::Kind::kScan:
      r.recorder.OnScan(*call.scan);
      break;
    case RecorderCall::Kind::kSwitch:
      if (SwitchesMaps(r.mode)) {
        r.recorder.CloseMap();
        ++r.next_switch;
      }
      break;
  }
}

// Makes a drive's calls on its recorders: each recorder belongs to one lane, which makes all of
// its calls in the drive's order — lane 0 in the drive's thread as the call is made, the others
// each on a helper thread of its own while the drive's thread simulates on. So every recorder
// sees the same calls in the same order whatever the number of lanes, and the bundles are the
// same.
class RecorderFeed {
 public:
  // Lanes: min(threads, recorders); recorder i goes to lane i % lanes.
  RecorderFeed(std::vector<ModeRecorder>& recorders, int threads)
      : recorders_(recorders),
        lane_count_(std::clamp<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), 1,
                                            std::max<std::size_t>(recorders.size(), 1))) {
    for (std::size_t l = 1; l < lane_count_; ++l) helpers_.push_back(std::make_unique<Helper>());
    for (std::size_t l = 1; l < lane_count_; ++l)
      helpers_[l - 1]->thread = std::thread([this, l] { Serve(l); });
  }
  RecorderFeed(const RecorderFeed&) = delete;
  RecorderFeed& operator=(const RecorderFeed&) = delete;
  // After an error of the drive: the helpers drop the calls not yet made.
  ~RecorderFeed() { Stop(/*drop=*/true); }

  bool parallel() const { return !helpers_.empty(); }
  // s: the helpers' thread CPU time, once they have finished.
  double HelperCpuSeconds() const {
    double total = 0.0;
    for (const std::unique_ptr<Helper>& h : helpers_) total += h->cpu_s;
    return total;
  }

  void Call(const RecorderCall& call) {
    for (std::size_t l = 1; l < lane_count_; ++l) {
      Helper& h = *helpers_[l - 1];
      std::unique_lock lock(h.mutex);
      // A bounded queue: the drive waits rather than hold many scans.
      h.changed.wait(lock, [&] { return h.calls.size() < kMaxQueued; });
      h.calls.push_back(call);
      h.changed.notify_all();
    }
    for (std::size_t i = 0; i < recorders_.size(); i += lane_count_) Apply(call, recorders_[i]);
  }

  // Waits until every call is made; rethrows the first error of a helper's recorder.
  void Finish() {
    Stop(/*drop=*/false);
    for (const std::unique_ptr<Helper>& h : helpers_) {
      if (h->error) std::rethrow_exception(h->error);
    }
  }

 private:
  static constexpr std::size_t kMaxQueued = 256;

  struct Helper {
    std::mutex mutex;
    std::condition_variable changed;
    std::deque<RecorderCall> calls;
    bool closed = false;  // no more calls come
    bool drop = false;    // leave the calls not yet made
    std::exception_ptr error;
    double cpu_s = 0.0;  // the thread's CPU time
    std::thread thread;
  };

  void Serve(std::size_t lane) {
    Helper& h = *helpers_[lane - 1];
    const double cpu_start = ThreadCpuSeconds();
    ServeCalls(lane, h);
    h.cpu_s = ThreadCpuSeconds() - cpu_start;
  }

  void ServeCalls(std::size_t lane, Helper& h) {
    for (;;) {
      RecorderCall call;
      {
        std::unique_lock lock(h.mutex);
        h.changed.wait(lock, [&] { return !h.calls.empty() || h.closed; });
        if (h.calls.empty() || h.drop) return;
        call = std::move(h.calls.front());
        h.calls.pop_front();
        h.changed.notify_all();
      }
      if (h.error) continue;  // after an error, only drain
      try {
        for (std::size_t i = lane; i < recorders_.size(); i += lane_count_)
          Apply(call, recorders_[i]);
      } catch (...) {
        h.error = std::current_exception();
      }
    }
  }

  void Stop(bool drop) {
    for (const std::unique_ptr<Helper>& h : helpers_) {
      {
        std::lock_guard lock(h->mutex);
        h->closed = true;
        h->drop = h->drop || drop;
      }
      h->changed.notify_all();
    }
    for (const std::unique_ptr<Helper>& h : helpers_) {
      if (h->thread.joinable()) h->thread.join();
    }
  }

  std::vector<ModeRecorder>& recorders_;
  std::size_t lane_count_;
  std::vector<std::unique_ptr<Helper>> helpers_;
};

// The recorders' share of one simulator step: the pose of each mode's source at an odometry
// tick, the scan.
void FeedRecorders(const sim::SimStep& s, const sim::Simulator& simulator,
                   const core::Pose2& X_RW_start, RecorderFeed& feed) {
  if (s.odometry) {
    RecorderCall call;
    call.kind = RecorderCall::Kind::kPose;
    call.X_OR = simulator.OdometryPose();
    // The consistent map's pose source is ground truth, expressed from the start so that its
    // frame M_0 is the teaching start like the odometry maps'.
    call.X_M0R = X_RW_start * simulator.RobotPose();
    feed.Call(call);
  }
  if (s.lidar) {
    RecorderCall call;
    call.kind = RecorderCall::Kind::kScan;
    // A helper needs its own copy; the drive's thread alone can use the step's scan.
    call.scan = feed.parallel() ? std::make_shared<const core::LaserScan>(s.lidar->scan)
                                : std::shared_ptr<const core::LaserScan>(
                                      std::shared_ptr<const core::LaserScan>(), &s.lidar->scan);
    feed.Call(call);
  }
}

// The operator's switch signals due at the teacher's progress, through the feed (none are listed
// with online switching): as SignalSwitches, every recorder that switches maps gets the same.
void SignalSwitchesThroughFeed(const std::vector<double>& switch_points, double progress,
                               std::size_t* signalled, RecorderFeed& feed) {
  while (*signalled < switch_points.size() && progress >= switch_points[*signalled]) {
    RecorderCall call;
    call.kind = RecorderCall::Kind::kSwitch;
    feed.Call(call);
    ++*signalled;
  }
}

// The recorders of a simulated teaching drive, switching online when the scenario does.
std::vector<ModeRecorder> DriveRecorders(const Scenario& scenario,
                                         const std::vector<MapMode>& modes) {
  RequireSwitchingModeIfOnline(scenario, modes);
  const std::optional<nav::OnlineSwitchingConfig> online =
      scenario.switching_online() ? std::optional(scenario.config.route.OnlineSwitching())
                                  : std::nullopt;
  return MakeModeRecorders(modes, scenario.config.nav, scenario.robot, online);
}

}  // namespace

TeachResult RunTeachDrive(const Scenario& scenario, const std::vector<MapMode>& modes,
                          const ProgressFn& progress, SensorTap* tap, int threads) {
  const double cpu_start = ThreadCpuSeconds();
  const ScenarioConfig& config = scenario.config;
  const core::Rng rng = core::Rng(config.seed).Split("teach");

  sim::World world = scenario.teach_world;
  if (!config.teach.pedestrians) world.config.pedestrians.clear();
  sim::Simulator simulator(world, config.sim, scenario.X_W_start, rng.Split("sim"));
  sim::Teacher teacher(scenario.route, config.teach.teacher, rng.Split("teacher"));
  ScriptedEvents events(config.events, EventPhase::kTeach);

  std::vector<ModeRecorder> recorders = DriveRecorders(scenario, modes);
  // The odometry ticks, for the per-map traces.
  std::vector<double> tick_time;
  std::vector<core::Pose2> tick_X_WR;

  TeachResult result;
  TeachTrace trace;
  const core::Pose2 X_RW_start = simulator.RobotPose().Inverse();
  Stepper stepper(simulator, config.nav.control_rate_hz, progress);
  stepper.SetTap(tap);
  const double timeout = TeachTimeout(scenario);
  const std::vector<double>& switch_points = config.route.switch_points.value;
  std::size_t switches_signalled = 0;
  core::Twist command;
  RecorderFeed feed(recorders, threads);

  for (;;) {
    if (stepper.ControlDue()) {
      const core::Pose2 X_WR = simulator.RobotPose();
      trace.time.push_back(simulator.time());
      trace.X_WR.push_back(X_WR);
      trace.X_OR.push_back(simulator.OdometryPose());
      if (teacher.Done()) break;
      if (simulator.time() > timeout) throw TeacherStuck(scenario, timeout, X_WR, teacher);
      command = teacher.Command(X_WR, stepper.control_dt());
      SignalSwitchesThroughFeed(switch_points, teacher.Progress(), &switches_signalled, feed);
      for (const std::string& name : events.Fire(simulator.time(), teacher.Progress(), simulator)) {
        result.events.push_back(core::FormatNumber(simulator.time()) + " " + name);
      }
    }
    const sim::SimStep s = stepper.Step(command);
    if (s.odometry) {
      tick_time.push_back(s.time);
      tick_X_WR.push_back(simulator.RobotPose());
    }
    FeedRecorders(s, simulator, X_RW_start, feed);
  }
  feed.Finish();

  if (tap != nullptr) tap->OnEnd();
  result.collisions = stepper.collisions();
  result.duration_s = simulator.time();
  result.modes =
      FinishModeRecorders(recorders, trace, tick_time, tick_X_WR, scenario.config.route);
  result.cpu_time_s = ThreadCpuSeconds() - cpu_start + feed.HelperCpuSeconds();
  return result;
}

}  // namespace retrace::bench
