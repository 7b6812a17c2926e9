#include "bench/engine/teach_drive.hpp"

#include <cstdint>
#include <optional>

#include "bench/engine/scripted_events.hpp"
#include "bench/engine/stepper.hpp"
#include "bench/engine/thread_cpu_time.hpp"
#include "core/check.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
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
                                           const std::vector<core::Pose2>& X_WR) {
  std::vector<ModeTeach> teaches;
  for (ModeRecorder& r : recorders) {
    ModeTeach m;
    m.mode = r.mode;
    m.bundle = r.recorder.Finish();  // first: it integrates the keyframes held back (online)
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

// The recorders' share of one simulator step: the pose of each mode's source at an odometry
// tick, the scan.
void FeedRecorders(const sim::SimStep& s, const sim::Simulator& simulator,
                   const core::Pose2& X_RW_start, std::vector<ModeRecorder>& recorders) {
  if (s.odometry) {
    const core::Pose2 X_WR = simulator.RobotPose();
    for (ModeRecorder& r : recorders) {
      // The consistent map's pose source is ground truth, expressed from the start so that
      // its frame M_0 is the teaching start like the odometry maps'.
      r.recorder.OnPose(r.mode == MapMode::kConsistent ? X_RW_start * X_WR
                                                       : simulator.OdometryPose());
    }
  }
  if (s.lidar) {
    for (ModeRecorder& r : recorders) r.recorder.OnScan(s.lidar->scan);
  }
}

}  // namespace

TeachResult RunTeachDrive(const Scenario& scenario, const std::vector<MapMode>& modes,
                          const ProgressFn& progress, SensorTap* tap) {
  const double cpu_start = ThreadCpuSeconds();
  const ScenarioConfig& config = scenario.config;
  const core::Rng rng = core::Rng(config.seed).Split("teach");

  sim::World world = scenario.teach_world;
  if (!config.teach.pedestrians) world.config.pedestrians.clear();
  sim::Simulator simulator(world, config.sim, scenario.X_W_start, rng.Split("sim"));
  sim::Teacher teacher(scenario.route, config.teach.teacher, rng.Split("teacher"));
  ScriptedEvents events(config.events, EventPhase::kTeach);

  RequireSwitchingModeIfOnline(scenario, modes);
  const std::optional<nav::OnlineSwitchingConfig> online =
      scenario.switching_online() ? std::optional(config.route.OnlineSwitching()) : std::nullopt;
  std::vector<ModeRecorder> recorders =
      MakeModeRecorders(modes, config.nav, scenario.robot, online);
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
  core::Twist command;

  for (;;) {
    if (stepper.ControlDue()) {
      const core::Pose2 X_WR = simulator.RobotPose();
      trace.time.push_back(simulator.time());
      trace.X_WR.push_back(X_WR);
      trace.X_OR.push_back(simulator.OdometryPose());
      if (teacher.Done()) break;
      if (simulator.time() > timeout) throw TeacherStuck(scenario, timeout, X_WR, teacher);
      command = teacher.Command(X_WR, stepper.control_dt());
      // The operator's switch signal, given as the teacher's progress passes a switch point
      // (none are listed with online switching).
      SignalSwitches(recorders, switch_points, teacher.Progress());
      for (const std::string& name : events.Fire(simulator.time(), teacher.Progress(), simulator)) {
        result.events.push_back(core::FormatNumber(simulator.time()) + " " + name);
      }
    }
    const sim::SimStep s = stepper.Step(command);
    if (s.odometry) {
      tick_time.push_back(s.time);
      tick_X_WR.push_back(simulator.RobotPose());
    }
    FeedRecorders(s, simulator, X_RW_start, recorders);
  }

  if (tap != nullptr) tap->OnEnd();
  result.collisions = stepper.collisions();
  result.duration_s = simulator.time();
  result.modes = FinishModeRecorders(recorders, trace, tick_time, tick_X_WR);
  result.cpu_time_s = ThreadCpuSeconds() - cpu_start;
  return result;
}

}  // namespace retrace::bench
