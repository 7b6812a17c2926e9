#include "bench/replay/log_teach.hpp"

#include <optional>

#include "bench/engine/switch_points.hpp"
#include "bench/engine/thread_cpu_time.hpp"
#include "core/errors.hpp"
#include "nav/teach_recorder.hpp"

namespace retrace::bench {

namespace {

// One scan of the window with the poses it is taught at.
struct ScanPoses {
  core::Pose2 X_OR;
  std::optional<core::Pose2> X_WR;
};

std::optional<ScanPoses> PosesAt(const LogStreams& streams, double stamp) {
  const std::optional<core::Pose2> X_OR = logs::PoseAt(streams.odometry, stamp);
  if (!X_OR) return std::nullopt;
  if (streams.reference.empty()) return ScanPoses{*X_OR, std::nullopt};
  const std::optional<core::Pose2> X_WR = logs::PoseAt(streams.reference, stamp);
  if (!X_WR) return std::nullopt;
  return ScanPoses{*X_OR, X_WR};
}

// The driven path, for automatic switch points: the position (reference, else odometry) at every
// scan of the window that has its poses, without repeats closer than 1 cm.
std::vector<core::Vec2> DrivenPath(const logs::LogIndex& index, const LogStreams& streams,
                                   const LogWindow& window) {
  std::vector<core::Vec2> path;
  logs::ReadScans(index, window.from_s, window.to_s, [&](const logs::ScanMessage& m, double) {
    const std::optional<ScanPoses> poses = PosesAt(streams, m.scan.stamp);
    if (!poses) return;
    const core::Vec2 p = poses->X_WR ? poses->X_WR->translation() : poses->X_OR.translation();
    if (path.empty() || (p - path.back()).norm() >= 0.01) path.push_back(p);
  });
  return path;
}

// The switch points known before teaching: suggested from the driven path (auto) or given;
// none when online (the recorders choose them while teaching).
std::vector<double> PlannedSwitchPoints(const logs::LogIndex& index, const LogStreams& streams,
                                        const LogConfig& config, const LogWindow& window) {
  if (config.route.switch_points.is(SwitchPlanning::kAuto)) {
    const std::vector<core::Vec2> path = DrivenPath(index, streams, window);
    if (path.size() >= 2) return SuggestSwitchPoints(path, config.route.revisit_radius);
    return {};
  }
  if (config.route.switch_points.is(SwitchPlanning::kOnline)) return {};
  return config.route.switch_points.value;
}

// The window held two scans with their poses at least, and the drive reached every switch point.
void RequireTaughtDrive(const logs::LogIndex& index, const LogStreams& streams,
                        const LogWindow& window, const LogTeachResult& result) {
  if (result.scans < 2) {
    throw core::IoError(index.name + ": fewer than two scans with odometry" +
                        std::string(streams.reference.empty() ? "" : " and reference") +
                        " between " + core::FormatNumber(window.from_s) + " and " +
                        core::FormatNumber(window.to_s) + " s of the log");
  }
  if (!result.switch_points.empty() && result.switch_points.back() >= result.driven_m) {
    throw core::ConfigError("route.switch_points", "the last switch point, " +
                                                       ArcLengthText(result.switch_points.back()) +
                                                       ", lies beyond the driven path (" +
                                                       ArcLengthText(result.driven_m) + ")");
  }
}

}  // namespace

std::vector<MapMode> LogTeachModes(const LogConfig& config, const LogStreams& streams) {
  std::vector<MapMode> modes = config.modes;
  if (modes.empty()) {
    modes = {MapMode::kPartial, MapMode::kScanMatched};
    if (!streams.reference.empty()) modes.push_back(MapMode::kConsistent);
  }
  for (MapMode mode : modes) {
    if (mode == MapMode::kConsistent && streams.reference.empty()) {
      throw core::ConfigError("modes",
                              "consistent needs a reference trajectory: the log has none (give "
                              "--reference FILE, or --synthetic-odometry for a corrected log)");
    }
  }
  // Online switching (the default) cuts the maps of the modes that switch; a consistent or single
  // map is one map whatever the switch points say, so asking for those modes alone is no error.
  return modes;
}

LogTeachResult RunLogTeach(const logs::LogIndex& index, const LogStreams& streams,
                           const LogConfig& config, const LogWindow& window) {
  const double cpu_start = ThreadCpuSeconds();
  const std::vector<MapMode> modes = LogTeachModes(config, streams);
  LogTeachResult result;

  const bool online = config.route.switch_points.is(SwitchPlanning::kOnline);
  result.switch_points = PlannedSwitchPoints(index, streams, config, window);
  std::optional<nav::OnlineSwitchingConfig> online_config;
  if (online) {
    online_config = config.route.OnlineSwitching();
  }
  std::vector<ModeRecorder> recorders =
      MakeModeRecorders(modes, config.nav, streams.robot, online_config);

  TeachTrace trace;
  std::optional<core::Pose2> X_RW_start;  // the consistent map's origin: the first reference pose
  std::optional<core::Vec2> last_position;
  logs::ReadScans(index, window.from_s, window.to_s, [&](const logs::ScanMessage& m, double t) {
    const std::optional<ScanPoses> poses = PosesAt(streams, m.scan.stamp);
    if (!poses) {
      ++result.scans_outside;
      return;
    }
    if (result.scans == 0) {
      result.first_s = t;
      if (poses->X_WR) X_RW_start = poses->X_WR->Inverse();
    }
    result.last_s = t;
    ++result.scans;
    const core::Vec2 position =
        poses->X_WR ? poses->X_WR->translation() : poses->X_OR.translation();
    if (last_position) result.driven_m += (position - *last_position).norm();
    last_position = position;

    SignalSwitches(recorders, result.switch_points, result.driven_m);
    trace.time.push_back(m.scan.stamp);
    trace.X_OR.push_back(poses->X_OR);
    if (poses->X_WR) trace.X_WR.push_back(*poses->X_WR);
    for (ModeRecorder& r : recorders) {
      r.recorder.OnPose(r.mode == MapMode::kConsistent ? *X_RW_start * *poses->X_WR : poses->X_OR);
      r.recorder.OnScan(m.scan);
    }
  });
  RequireTaughtDrive(index, streams, window, result);

  result.modes = FinishModeRecorders(recorders, trace, trace.time, trace.X_WR, config.route);
  result.cpu_time_s = ThreadCpuSeconds() - cpu_start;
  return result;
}

}  // namespace retrace::bench
