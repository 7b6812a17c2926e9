#include "bench/run/stepped_episode.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "bench/engine/mode_list.hpp"
#include "bench/engine/playback.hpp"
#include "bench/engine/playback_episode.hpp"
#include "bench/engine/sensor_tap.hpp"
#include "bench/engine/stack_registry.hpp"
#include "bench/metrics/experiment.hpp"
#include "bench/stack/navigation_stack.hpp"
#include "core/check.hpp"
#include "core/errors.hpp"
#include "core/path_projection.hpp"

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

// The checks of SteppedEpisode::Act on a caller's answer.
void CheckAnswer(const StackOutput& answer, std::size_t maps) {
  const auto check_map = [maps](std::size_t map) {
    if (map >= maps) {
      throw core::ConfigError("answer", "map " + std::to_string(map) +
                                            " is not a map of the route (it has " +
                                            std::to_string(maps) + ")");
    }
  };
  check_map(answer.map);
  RequireFinite(answer.X_MR, "the estimate");
  if (!std::isfinite(answer.drive.command.v) || !std::isfinite(answer.drive.command.omega)) {
    throw core::ConfigError("answer", "the command must be finite");
  }
  if (const std::optional<MapChange>& change = answer.map_change) {
    check_map(change->from);
    if (change->to != answer.map) {
      throw core::ConfigError("answer", "a map_change into map " + std::to_string(change->to) +
                                            " answered in map " + std::to_string(answer.map));
    }
    RequireFinite(change->X_MkR, "the map_change's estimate before");
    RequireFinite(change->X_MnR, "the map_change's estimate after");
  }
}

}  // namespace

// The stack the episode sees: it records each step's sensor data for the caller, and answers
// with retrace's own stack (builtin) or with the caller's answer.
class ObservingStack final : public NavigationStack {
 public:
  explicit ObservingStack(std::unique_ptr<NavigationStack> builtin)
      : builtin_(std::move(builtin)) {}

  Observation observation;
  std::optional<StackOutput> answer;

  void OnOdometry(double t, const core::OdometryDelta& delta) override {
    observation.odometry.push_back({t, delta});
    if (builtin_) builtin_->OnOdometry(t, delta);
  }
  void OnScan(const core::LaserScan& scan) override {
    observation.scans.push_back(scan);
    if (builtin_) builtin_->OnScan(scan);
  }
  StackOutput OnControlTick(double t, double dt) override {
    if (builtin_) return builtin_->OnControlTick(t, dt);
    StackOutput out = *answer;
    map_changes_.Apply(&out);
    return out;
  }
  std::optional<MapChange> Resume(StackOutput* out) override {
    if (builtin_) return builtin_->Resume(out);
    handed_back_ = true;  // told with the next observation
    return std::nullopt;
  }
  // Whether the robot was handed back since the last call.
  bool TakeHandedBack() { return std::exchange(handed_back_, false); }
  const StackInsight* insight() const override { return builtin_ ? builtin_->insight() : nullptr; }
  bool builtin() const { return builtin_ != nullptr; }

 private:
  std::unique_ptr<NavigationStack> builtin_;
  MapChangeTracker map_changes_;
  bool handed_back_ = false;
};

std::shared_ptr<const SteppedTeaching> TeachForStepping(const TeachingRequest& request,
                                                        ProgressSink* progress) {
  const std::vector<MapMode> modes = ParseModeList({request.mode}, "mode");
  if (modes.size() != 1) throw core::ConfigError("mode", "one map mode, not 'all'");
  auto teaching = std::make_shared<SteppedTeaching>();
  teaching->scenario = LoadScenario(
      request.scenario, CommandLineOverrides(request.overrides, request.seed, std::nullopt));
  RecordingTap tap(&teaching->recording);
  if (progress != nullptr) progress->Phase("teach", 1);
  TeachResult taught = RunTeachDrive(teaching->scenario, modes, SimTimeReporter(progress), &tap);
  if (progress != nullptr) progress->UnitDone();
  teaching->teach = std::move(taught.modes.front());
  teaching->duration_s = taught.duration_s;
  return teaching;
}

AggregateMetrics AggregateSteppedRuns(const SteppedTeaching& teaching,
                                      const std::vector<const RunTrace*>& runs) {
  std::vector<RunTrace> traces;
  std::vector<RunMetrics> metrics;
  for (const RunTrace* run : runs) {
    traces.push_back(*run);
    metrics.push_back(
        ComputeRunMetrics(teaching.teach.trace, *run, teaching.scenario.config.metrics));
  }
  return AggregateMode(teaching.scenario, teaching.teach, traces, metrics);
}

struct SteppedEpisode::State {
  std::shared_ptr<const SteppedTeaching> teaching;
  int run = 0;
  std::unique_ptr<ObservingStack> stack;
  std::unique_ptr<PlaybackEpisode> episode;
  bool observed = false;
  std::optional<RunTrace> trace;
};

SteppedEpisode::SteppedEpisode(std::shared_ptr<const SteppedTeaching> teaching, int run,
                               bool builtin)
    : state_(std::make_unique<State>()) {
  if (run < 0) throw core::ConfigError("run", "must be >= 0");
  RETRACE_CHECK(teaching != nullptr);
  State& s = *state_;
  s.teaching = std::move(teaching);
  s.run = run;
  const SteppedTeaching& t = *s.teaching;
  std::unique_ptr<NavigationStack> stack;
  if (builtin) stack = MakeStack(t.scenario, t.teach.bundle, run);
  s.stack = std::make_unique<ObservingStack>(std::move(stack));
  s.episode =
      std::make_unique<PlaybackEpisode>(t.scenario, t.teach.bundle, t.teach.trace, run,
                                        PlaybackTimeout(t.scenario, t.duration_s), *s.stack);
}

SteppedEpisode::~SteppedEpisode() = default;

const SteppedTeaching& SteppedEpisode::teaching() const { return *state_->teaching; }
int SteppedEpisode::run() const { return state_->run; }
std::size_t SteppedEpisode::maps() const { return state_->teaching->teach.bundle.maps.size(); }
bool SteppedEpisode::done() const { return state_->episode->done(); }

const Observation& SteppedEpisode::Observe() {
  State& s = *state_;
  if (s.episode->done()) throw core::ConfigError("step", "the run is done");
  if (s.observed) throw core::ConfigError("step", "answer the last observation first (act)");
  s.stack->observation = {};
  s.stack->observation.handed_back = s.stack->TakeHandedBack();
  s.episode->Sense();
  s.stack->observation.time = s.episode->time();
  s.observed = true;
  return s.stack->observation;
}

bool SteppedEpisode::Act(const std::optional<StackOutput>& answer) {
  State& s = *state_;
  if (!s.observed) throw core::ConfigError("step", "observe before acting");
  if (!s.stack->builtin()) {
    if (!answer) throw core::ConfigError("answer", "the episode has no builtin stack: answer");
    CheckAnswer(*answer, maps());
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

const PlaybackSample* SteppedEpisode::LastSample() const {
  const State& s = *state_;
  if (s.trace) return s.trace->samples.empty() ? nullptr : &s.trace->samples.back();
  return s.episode->last_sample();
}

std::size_t SteppedEpisode::Collisions() const {
  const State& s = *state_;
  return s.trace ? s.trace->collisions.size() : s.episode->collisions();
}

RunMetrics SteppedEpisode::Metrics() {
  const SteppedTeaching& t = *state_->teaching;
  return ComputeRunMetrics(t.teach.trace, trace(), t.scenario.config.metrics);
}

}  // namespace retrace::bench
