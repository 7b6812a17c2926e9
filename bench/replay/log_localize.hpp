#pragma once
// `retrace log-localize`: the playback phase's localization on a recorded log (docs/DESIGN.md
// §10). The localizer (with dynamic scan point rejection) and the map server of playback run
// through the log's scans and odometry: each odometry step between two samples is one
// prediction, each scan one measurement update (gated by motion as in playback), and the map
// switches by eq. (1) when the estimate reaches the end of the current taught path, measured
// by the path follower's forward projection — the same "how far along" as playback. Nothing
// commands the robot: the log drove it. A taught route that is a loop — its last path ends where
// map 0's began, through the chain of switch poses, within route.revisit_radius plus
// route.online_drift times its length — goes on in map 0 after its last map, so that a log that
// drives the loop again and again is localized lap after lap.
//
// Against a reference the error is measured as in simulated runs: the local truth
// (bench/engine/local_truth.hpp) of the teaching drive's trace, the reference standing in for
// ground truth in both the teach folder and this run.

#include <cstdint>
#include <optional>
#include <vector>

#include "bench/engine/snapshot.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/engine/trace.hpp"
#include "bench/replay/log_config.hpp"
#include "bench/replay/log_streams.hpp"
#include "bench/replay/log_teach.hpp"
#include "core/rng.hpp"
#include "logs/sensor_log.hpp"

namespace retrace::bench {

/// One scan of the run.
struct LogLocalizeSample {
  double time = 0.0;  ///< the scan's stamp (s)
  int map = 0;
  core::Pose2 X_MR;                       ///< the estimate in map `map`
  core::Pose2 X_OR;                       ///< the odometry at the scan's stamp
  bool lost = false;                      ///< the localizer's own verdict
  bool off_map = false;                   ///< no map covers the place: odometry only
  std::optional<core::Pose2> X_WR;        ///< the reference
  std::optional<core::Pose2> X_MR_truth;  ///< the local truth (reference and teach trace)
};

struct LogLocalizeResult {
  std::vector<LogLocalizeSample> samples;
  std::vector<LocalizerSample> updates;  ///< the updates that ran (no pedestrian labels)
  std::vector<SwitchRecord> switches;    ///< X_WR: the reference, or the identity without
  /// The update with the most rejected beams while localized (error within metrics.lost_error)
  std::optional<LocalizationSnapshot> snapshot;
  double first_s = 0.0;  ///< log time of the first scan used
  double last_s = 0.0;
  std::size_t scans_outside = 0;  ///< scans in the window without odometry
  /// The taught route is a loop: after its last map the run goes on in map 0 (the loop driven
  /// again; nav::MapServer::WrapPlace).
  bool loop = false;
  /// Times the estimate reached the end of the last taught path.
  int laps_completed = 0;
  double cpu_time_s = 0.0;
};

struct LogReplayOptions {
  /// Where the localizer starts in map 0. Unset: with a reference and a teach trace that has
  /// one, the local truth of the first scan (the operator knows where the robot stands, as the
  /// simulator's playback starts at the teaching start); else map 0's origin.
  std::optional<core::Pose2> initial;
  /// One prediction per odometry message, as the simulator's playback predicts, instead of the
  /// fewest arcs that follow the messages within 1 mm.
  bool every_odometry_tick = false;
};

/// The localizer's random stream for a seed: that of playback run 0 of a scenario with the same
/// seed, so that a simulated run recorded with `retrace run --record-log` replays with the same
/// draws.
core::Rng LogLocalizeRng(std::uint64_t seed);

/// Drives nav::Navigator, the simulator's playback step, through the log: per scan the
/// odometry since the previous scan (PredictBetween), the update, then one control tick.
/// Throws core::IoError for a window without scans with odometry, core::ConfigError for a teach
/// folder whose trace does not hold the maps it has.
LogLocalizeResult RunLogLocalize(const logs::LogIndex& index, const LogStreams& streams,
                                 const ModeTeach& teach, const LogConfig& config,
                                 const LogWindow& window, const LogReplayOptions& options = {});

}  // namespace retrace::bench
