#include "bench/engine/teach_drive.hpp"

#include <cstdint>
#include <optional>

#include "bench/engine/scripted_events.hpp"
#include "bench/engine/stepper.hpp"
#include "bench/engine/thread_cpu_time.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "nav/teach_recorder.hpp"
#include "sim/simulator.hpp"
#include "sim/teacher.hpp"

namespace retrace::bench {

namespace {

// One mode's recorder and its references, fed from the shared drive.
struct ModeRecorder {
  MapMode mode;
  nav::TeachRecorder recorder;
  std::vector<TeachMapTrace> maps{1};
  std::size_t next_switch = 0;
};

}  // namespace

TeachResult RunTeachDrive(const Scenario& scenario, const std::vector<MapMode>& modes,
                          const ProgressFn& progress) {
  const double cpu_start = ThreadCpuSeconds();
  const ScenarioConfig& config = scenario.config;
  const core::Rng rng = core::Rng(config.seed).Split("teach");

  sim::World world = scenario.teach_world;
  if (!config.teach.pedestrians) world.config.pedestrians.clear();
  sim::Simulator simulator(world, config.sim, scenario.X_W_start, rng.Split("sim"));
  sim::Teacher teacher(scenario.route, config.teach.teacher, rng.Split("teacher"));
  ScriptedEvents events(config.events, EventPhase::kTeach);

  std::vector<ModeRecorder> recorders;
  recorders.reserve(modes.size());
  for (MapMode mode : modes) {
    std::optional<nav::ScanMatcherConfig> matcher;
    if (mode == MapMode::kScanMatched) matcher = config.nav.scan_matcher;
    recorders.push_back({mode, nav::TeachRecorder(config.nav.mapper, scenario.robot, matcher)});
  }

  TeachResult result;
  TeachTrace trace;
  const core::Pose2 X_RW_start = simulator.RobotPose().Inverse();
  Stepper stepper(simulator, config.nav.control_rate_hz, progress);
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
      if (simulator.time() > timeout) {
        throw core::WorldError(
            scenario.source.string() + ": the teacher did not finish the route within " +
            core::FormatNumber(timeout) + " s; stuck at (" + core::FormatNumber(X_WR.x) + ", " +
            core::FormatNumber(X_WR.y) + "), " + core::FormatNumber(teacher.Progress()) +
            " m along the route");
      }
      command = teacher.Command(X_WR, stepper.control_dt());
      // The operator's switch signal, given as the teacher's progress passes a switch point.
      for (ModeRecorder& r : recorders) {
        if (!SwitchesMaps(r.mode)) continue;
        while (r.next_switch < switch_points.size() &&
               teacher.Progress() >= switch_points[r.next_switch]) {
          r.recorder.CloseMap();
          r.maps.emplace_back();
          ++r.next_switch;
        }
      }
      for (const std::string& name : events.Fire(simulator.time(), teacher.Progress(), simulator)) {
        result.events.push_back(core::FormatNumber(simulator.time()) + " " + name);
      }
    }
    const sim::SimStep s = stepper.Step(command);
    if (s.odometry) {
      const core::Pose2 X_WR = simulator.RobotPose();
      for (ModeRecorder& r : recorders) {
        // The consistent map's pose source is ground truth, expressed from the start so that
        // its frame M_0 is the teaching start like the odometry maps'.
        r.recorder.OnPose(r.mode == MapMode::kConsistent ? X_RW_start * X_WR
                                                         : simulator.OdometryPose());
        r.maps.back().time.push_back(s.time);
        r.maps.back().X_MR.push_back(r.recorder.pose());
        r.maps.back().X_WR.push_back(X_WR);
      }
    }
    if (s.lidar) {
      for (ModeRecorder& r : recorders) r.recorder.OnScan(s.lidar->scan);
    }
  }

  result.collisions = stepper.collisions();
  result.duration_s = simulator.time();
  for (ModeRecorder& r : recorders) {
    ModeTeach m;
    m.mode = r.mode;
    m.match_counts = r.recorder.match_counts();
    m.bundle = r.recorder.Finish();
    m.trace = trace;
    m.trace.maps = std::move(r.maps);
    result.modes.push_back(std::move(m));
  }
  result.cpu_time_s = ThreadCpuSeconds() - cpu_start;
  return result;
}

}  // namespace retrace::bench
