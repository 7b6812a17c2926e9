#include "bench/run/stepped_episode.hpp"

#include <cmath>
#include <utility>

#include "bench/engine/mode_list.hpp"
#include "bench/engine/navigation_stack.hpp"
#include "bench/engine/playback.hpp"
#include "bench/engine/playback_episode.hpp"
#include "bench/engine/sensor_tap.hpp"
#include "core/errors.hpp"
#include "nav/route_graph.hpp"

namespace retrace::bench {
namespace {

// The teaching drive's sensors into a TeachRecording.
class RecordingTap final : public SensorTap {
 public:
  explicit RecordingTap(TeachRecording* out) : out_(out) {}
  void OnOdometry(double time, const core::Pose2& X_OR, const core::Pose2& X_WR) override {
    out_->odometry.push_back({time, X_OR});
    out_->X_WR.push_back(X_WR);
  }
  void OnScan(const core::LaserScan& scan, const core::Pose2&, const core::Pose2&) override {
    out_->scans.push_back(scan);
  }
  void OnEnd() override {}

 private:
  TeachRecording* out_;
};

void RequireFinite(const core::Pose2& p, const char* what) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.theta)) {
    throw core::ConfigError("answer", std::string(what) + " must be finite");
  }
}

}  // namespace

// The stack the episode sees: it records each step's sensor data for the caller, and answers
// with retrace's own stack (builtin) or with the caller's answer.
class ObservingStack final : public NavigationStack {
 public:
  ObservingStack(std::unique_ptr<NavigationStack> builtin, const nav::TeachBundle& bundle)
      : builtin_(std::move(builtin)), bundle_(bundle) {}

  Observation observation;
  std::optional<StackAnswer> answer;

  void OnOdometry(double t, const core::OdometryDelta& delta) override {
    X_OR_ = core::IntegrateOdometry(X_OR_, delta);
    observation.odometry.push_back({t, X_OR_});
    if (builtin_) builtin_->OnOdometry(t, delta);
  }
  const nav::LocalizerUpdate* OnScan(const core::LaserScan& scan) override {
    observation.scans.push_back(scan);
    return builtin_ ? builtin_->OnScan(scan) : nullptr;
  }
  StackOutput OnControlTick(double t, double dt) override {
    if (builtin_) return builtin_->OnControlTick(t, dt);
    const StackAnswer& a = *answer;
    StackOutput out;
    out.drive = {.command = a.command};
    out.X_MR = a.X_MR;
    out.map = a.map;
    out.lost = a.lost;
    out.route_done = a.route_done;
    out.last_map = a.map + 1 == bundle_.maps.size();
    // Progress by the caller's own estimate, projected onto the taught path of its map.
    const core::Path& path = bundle_.maps[a.map].path;
    out.remaining = path.Length() - nav::Project(path, a.X_MR.translation()).s;
    if (a.map != map_) out.map_switch = nav::MapSwitch{map_, a.map, X_MR_, a.X_MR, 0.0};
    map_ = a.map;
    X_MR_ = a.X_MR;
    return out;
  }
  std::optional<nav::MapSwitch> Resume(StackOutput* out) override {
    return builtin_ ? builtin_->Resume(out) : std::nullopt;
  }
  const nav::Navigator* navigator() const override {
    return builtin_ ? builtin_->navigator() : nullptr;
  }
  bool builtin() const { return builtin_ != nullptr; }

 private:
  std::unique_ptr<NavigationStack> builtin_;
  const nav::TeachBundle& bundle_;
  core::Pose2 X_OR_;
  std::size_t map_ = 0;
  core::Pose2 X_MR_;
};

struct SteppedEpisode::State {
  Scenario scenario;
  ModeTeach teach;
  TeachRecording recording;
  std::unique_ptr<ObservingStack> stack;
  std::unique_ptr<PlaybackEpisode> episode;
  bool observed = false;
  std::optional<RunTrace> trace;
};

SteppedEpisode::SteppedEpisode(const EpisodeRequest& request) : state_(std::make_unique<State>()) {
  State& s = *state_;
  if (request.run < 0) throw core::ConfigError("run", "must be >= 0");
  const std::vector<MapMode> modes = ParseModeList({request.mode}, "mode");
  if (modes.size() != 1) throw core::ConfigError("mode", "one map mode, not 'all'");
  s.scenario = LoadScenario(request.scenario,
                            CommandLineOverrides(request.overrides, request.seed, std::nullopt));
  RecordingTap tap(&s.recording);
  TeachResult taught = RunTeachDrive(s.scenario, modes, {}, &tap);
  s.teach = std::move(taught.modes.front());
  std::unique_ptr<NavigationStack> builtin;
  if (request.builtin) builtin = MakeStack(s.scenario, s.teach.bundle, request.run);
  s.stack = std::make_unique<ObservingStack>(std::move(builtin), s.teach.bundle);
  s.episode =
      std::make_unique<PlaybackEpisode>(s.scenario, s.teach.trace, request.run,
                                        PlaybackTimeout(s.scenario, taught.duration_s), *s.stack);
}

SteppedEpisode::~SteppedEpisode() = default;

const Scenario& SteppedEpisode::scenario() const { return state_->scenario; }
const ModeTeach& SteppedEpisode::teach() const { return state_->teach; }
const TeachRecording& SteppedEpisode::recording() const { return state_->recording; }
std::size_t SteppedEpisode::maps() const { return state_->teach.bundle.maps.size(); }
bool SteppedEpisode::done() const { return state_->episode->done(); }

const Observation& SteppedEpisode::Observe() {
  State& s = *state_;
  if (s.episode->done()) throw core::ConfigError("step", "the run is done");
  if (s.observed) throw core::ConfigError("step", "answer the last observation first (act)");
  s.stack->observation = {};
  s.episode->Sense();
  s.stack->observation.time = s.episode->time();
  s.observed = true;
  return s.stack->observation;
}

bool SteppedEpisode::Act(const std::optional<StackAnswer>& answer) {
  State& s = *state_;
  if (!s.observed) throw core::ConfigError("step", "observe before acting");
  if (!s.stack->builtin()) {
    if (!answer) throw core::ConfigError("answer", "the episode has no builtin stack: answer");
    if (answer->map >= maps()) {
      throw core::ConfigError("answer", "map " + std::to_string(answer->map) +
                                            " is not a map of the route (it has " +
                                            std::to_string(maps()) + ")");
    }
    RequireFinite(answer->X_MR, "the estimate");
    if (!std::isfinite(answer->command.v) || !std::isfinite(answer->command.omega)) {
      throw core::ConfigError("answer", "the command must be finite");
    }
  }
  s.stack->answer = answer;
  s.observed = false;
  return s.episode->Act();
}

const RunTrace& SteppedEpisode::trace() {
  State& s = *state_;
  if (!s.episode->done()) throw core::ConfigError("step", "the run is not done yet");
  if (!s.trace) s.trace = s.episode->Finish();
  return *s.trace;
}

RunMetrics SteppedEpisode::Metrics() {
  return ComputeRunMetrics(state_->teach.trace, trace(), state_->scenario.config.metrics);
}

}  // namespace retrace::bench
