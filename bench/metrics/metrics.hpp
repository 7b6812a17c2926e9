#pragma once
// Episode metrics (docs/DESIGN.md §6): per playback run and aggregated over the runs of one map
// mode, computed after the runs from the traces alone (bench/engine/trace.hpp), all from ground
// truth. Every playback sample is one control tick, so time-weighted = sample-weighted.
//
// Definitions
//
// Summary statistics (Summary) of a sample set: mean, RMS = sqrt(mean of squares), p95 = the
//   95th percentile by linear interpolation between order statistics (rank 0.95 (n - 1) of the
//   sorted samples), max, count. Non-finite samples are left out; an empty set gives NaN
//   statistics (null in JSON) and count 0.
//
// success, outcome: from RunTrace.outcome. time_s: time of the last sample (0 with none).
// path_length_m: sum of the ground-truth position steps between consecutive samples.
// progress_m: the furthest arc length (clamped to the taught path) that the run's ground
//   truth reached along the taught path, by the projection with progress tracking below.
//
// The taught path: the polyline through the teaching drive's ground-truth positions
//   (TeachTrace.X_WR; consecutive duplicates dropped), with its arc length s.
//
// tracking_error_m: per sample, the Euclidean distance from the run's ground-truth position to
//   the taught path (to its segments, not just its vertices; exact, via a spatial grid).
//   Summary per run.
//
// Progress tracking (used by the repeatability and by the localization match): the match is
//   searched in a window of arc length [s_prev - match_window, s_prev + match_window] around
//   the previous match (s_prev = 0 at the start of the run, or of map k for the localization
//   match); only if the windowed nearest is farther than match_fallback_distance is the whole
//   path searched, and the global result is taken if it is closer. A route that passes the
//   same place twice is thus matched on the right lap.
//
// localization_error_m / _rad: the estimate X_{M_k R} (sample.X_MR, k = sample.map_index)
//   against the local ground truth in M_k. j = the nearest teaching sample of map k
//   (TeachTrace.maps[k].X_WR positions, matched with progress tracking; restarted at the
//   start of map k whenever the map index changes); local truth
//     X_{M_k R}^true = X_{M_k R_j} * inverse(X_{W R_j}) * X_{W R};
//   error = distance of the positions (m) and |wrapped heading difference| (rad). Samples
//   whose map index has no (or an empty) teach map have no error and are left out.
//   Summary per run, and lost_fraction = the fraction of samples with an error whose position
//   error exceeds lost_error.
//
// localizer (bench/metrics/localizer_health.hpp): lost_time_s, the time the localizer deemed
//   itself lost (PlaybackSample.lost); lost_spells, how often it became lost; reacquisitions,
//   recovery trials that replaced its belief; max_jump_m, the largest move of the estimate
//   between two consecutive samples in the same map beyond what the odometry moved, and its time.
//   Aggregate: sums, and the largest jump of any run.
//
// repeatability (aggregate over runs): stations every station_spacing m of arc length along the
//   taught path, s = 0, spacing, 2 spacing, ... <= length. Each run's ground-truth positions
//   are projected onto the taught path with progress tracking, giving per sample (s, e), e
//   the signed lateral offset (> 0: left of the path direction; beyond the ends the first and
//   last segments are extended). The run's offset at a station is e interpolated linearly in
//   s between the first pair of consecutive samples with s_i <= s_station <= s_{i+1} and
//   s_i < s_{i+1} <= s_i + 2 m (a bigger jump is a discontinuity of the match, not a
//   crossing). A station that a run never crossed is missing (NaN) for that run. All runs
//   take part, whatever their outcome. Per station with >= 2 runs: the sample standard
//   deviation (n - 1) and the spread (max - min) across runs. repeatability_m = mean over
//   those stations of the standard deviation; repeatability_max_spread_m = max over them of
//   the spread; repeatability_stations_used = their number.
//
// collisions: contact events (RunTrace.collisions) of the same kind, and for pedestrians of
//   the same pedestrian id, form one incident while each follows the previous one by less
//   than collision_merge_time (chained). A pedestrian incident counts as robot_driving when, at
//   its first contact, the robot was moving towards the contact point faster than
//   collision_driving_speed: its ground-truth velocity over the last collision_speed_window
//   s before the contact (samples at or before it), projected on the direction from the
//   robot's centre to the contact point. The others are pedestrians walking into a robot that
//   stood, gave way or drove past. Reported: incidents and raw events per kind,
//   min_clearance_m = min over samples of the clearance to static geometry,
//   min_pedestrian_gap_m = min over samples of the gap to a pedestrian (null: none seen).
//
// switch error: for each map switch, the localization error (m, rad) of the transformed
//   estimate X_{M_n R} (SwitchRecord.X_MnR) against the local ground truth in map `to` at
//   SwitchRecord.X_WR, the match in map `to` started at its beginning. Per run the list, its
//   length (count) and the max; aggregate: count, mean and max over the switches of all runs
//   that have an error (a switch to a map the teach trace lacks has none: NaN).
//
// dynamic_points: over the localizer updates, rejected_fraction = sum rejected / sum tested
//   beams, precision = TP / (TP + FP), recall = TP / (TP + FN); NaN (null) when the
//   denominator is 0. Aggregate: the same from the totals over all runs.
//
// cpu: localizer measurement update time (thread CPU time of Update) mean and max in ms over the
//   updates; the run's thread CPU time cpu_time_s, simulated time sim_time_s and
//   real_time_factor = sim_time_s / cpu_time_s. Aggregate: totals, the factor of the totals,
//   and the update time mean (pooled over all updates) and max.
//
// social (Social navigation metrics; between the bodies' edges, i.e. centre distance minus
//   both radii, the robot a disc of its footprint's circumradius): intimate_time_s /
//   personal_time_s = time (s; each sample holds until the next) with the nearest pedestrian's
//   edge closer than intimate_zone (0.45 m) / personal_zone (1.2 m) to the robot's (Hall 1966).
//   min_ttc_s = min over samples and the pedestrians within 5 m (RunTrace.nearby) of the time
//   until the two discs touch if the robot kept its commanded velocity (sample.command.v along
//   its ground-truth heading, turning ignored) and the pedestrian its current velocity: the
//   smallest t >= 0 with |Δp + Δv t| = r_robot + r_pedestrian; 0 while they overlap; capped at
//   ttc_horizon (10 s: no collision course counts as 10). path_efficiency = the taught path's
//   length / path_length_m, time_efficiency = the teaching drive's duration / time_s, both for
//   successful runs only (NaN otherwise). jerk_m_s3 = Summary of |j| with v, a, j the
//   successive finite differences of the ground-truth position over the samples (central in
//   time: v between samples, a and j at the midpoints between those).
//   crowd: an encounter starts when a pedestrian's edge comes within personal_zone of the
//   robot's and ends when it is farther than personal_zone + 0.3 m (or out of the 5 m record, or
//   the run ends). Over it, the pedestrian is blocked if it stood (speed < 0.2 m/s) for 0.5 s or
//   more in total, yielded if not but walked slower than 0.7 of its desired speed for 0.5 s or
//   more, and passed otherwise; a person who stands still by design (pedestrian mode `stand`,
//   NearbyPedestrian::standing) is none of those but `standing`: its speed says nothing about
//   the robot. wait_time_s sums the standing time of the walkers' encounters, max_wait_s is the
//   longest. Aggregate: means over runs (zone times, jerk statistics), min (ttc), means
//   over successful runs (efficiencies), sums (crowd counts and wait) and max (max wait).
//   by_behaviour: the same per behaviour toward the robot (sim::RobotBehaviour) of the people met,
//   for the behaviours met at all: people (distinct pedestrians in the 5 m record), min_gap_m (the
//   closest any of them came), intimate_time_s / personal_time_s (time with one of them that
//   close) and their crowd reactions. stopped_by: for a run that did not succeed, the behaviour
//   of the reacting people (NearbyPedestrian::reacting) who spent the most time in the robot's
//   personal zone during its last stopped_by_window (30 s), if any: the behaviour that stopped
//   it. Aggregate: sums per behaviour (min of min_gap_m, means of the zone times over all runs)
//   and, per behaviour, the runs it stopped.
//
// Aggregate (AggregateMetrics): success rate and counts per outcome; for each per-run Summary
//   metric both `pooled` (the statistics of all samples of all runs together: what docs/RESULTS.md
//   reports) and `run_mean` (each statistic averaged over the runs that have samples; its
//   count is the number of those runs); means over runs of time_s, path_length_m, progress_m.
//
// JSON (ToJson; NaN and infinities are null). A Summary is {mean, rms, p95, max, count}, its
// unit in the key that holds it. Per run: run, seed, outcome, success, samples, time_s,
// path_length_m, progress_m, tracking_error_m, localization_error_m, localization_error_rad,
// lost_fraction, collisions {static_incidents, pedestrian_incidents,
// pedestrian_incidents_robot_driving, static_events,
// pedestrian_events, min_clearance_m, min_pedestrian_gap_m}, switch_error {count, max_m,
// max_rad, switches [{time_s, from, to, error_m, error_rad}]}, dynamic_points {beams_tested,
// beams_rejected, true_positive, false_positive, false_negative, rejected_fraction, precision,
// recall}, cpu {localizer_updates, localizer_update_mean_ms, localizer_update_max_ms,
// sim_time_s, cpu_time_s, real_time_factor}. Aggregate: runs, successes, success_rate,
// outcomes {success, timeout, collision, lost}, taught_path_length_m, mean_time_s,
// mean_path_length_m, mean_progress_m, tracking_error_m / localization_error_m /
// localization_error_rad {pooled, run_mean}, lost_fraction {pooled, run_mean},
// repeatability_m, repeatability_max_spread_m, repeatability_stations_used (the stations
// themselves go to repeatability.csv: WriteRepeatabilityCsv), collisions {as per run, totals and
// minima, plus runs_with_collision}, switch_error {count, mean_m, max_m, mean_rad, max_rad},
// dynamic_points {as per run, of the totals}, cpu {as per run, totals}.

#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <vector>

#include "bench/engine/metrics_config.hpp"
#include "bench/engine/trace.hpp"
#include "bench/metrics/localizer_health.hpp"
#include "bench/metrics/map_quality.hpp"
#include "bench/metrics/switching.hpp"

namespace retrace::bench {

inline constexpr double kMetricNaN = std::numeric_limits<double>::quiet_NaN();

/// Statistics of a sample set (see the definitions above); NaN and count 0 when empty.
struct Summary {
  double mean = kMetricNaN;
  double rms = kMetricNaN;
  double p95 = kMetricNaN;
  double max = kMetricNaN;
  int count = 0;
};

/// Summary of the finite values in `values`.
Summary Summarize(const std::vector<double>& values);

struct CollisionStats {
  int static_incidents = 0;
  int pedestrian_incidents = 0;
  int pedestrian_incidents_robot_driving = 0;  ///< of pedestrian_incidents: the robot drove in
  int static_events = 0;                       ///< raw contact events
  int pedestrian_events = 0;                   ///< raw contact events
  double min_clearance_m = kMetricNaN;         ///< NaN without samples
  /// NaN without samples, inf when no pedestrian was seen.
  double min_pedestrian_gap_m = kMetricNaN;
};

/// The localization error right after one map switch.
struct SwitchError {
  double time_s = 0.0;
  int from = 0;
  int to = 0;
  double error_m = kMetricNaN;  ///< NaN when map `to` has no teach trace
  double error_rad = kMetricNaN;
};

struct DynamicPointStats {
  std::int64_t beams_tested = 0;
  std::int64_t beams_rejected = 0;
  std::int64_t true_positive = 0;
  std::int64_t false_positive = 0;
  std::int64_t false_negative = 0;
  double rejected_fraction = kMetricNaN;  ///< rejected / tested
  double precision = kMetricNaN;          ///< TP / (TP + FP)
  double recall = kMetricNaN;             ///< TP / (TP + FN)
};

struct CpuStats {
  int localizer_updates = 0;
  double localizer_update_mean_ms = kMetricNaN;
  double localizer_update_max_ms = kMetricNaN;
  double sim_time_s = 0.0;
  double cpu_time_s = 0.0;
  double real_time_factor = kMetricNaN;  ///< sim_time_s / cpu_time_s; NaN when cpu_time_s <= 0
};

/// Thresholds of CrowdReaction (see the definitions above).
inline constexpr double kStopSpeed = 0.2;            ///< m/s: below this a pedestrian stands
inline constexpr double kYieldSpeedFraction = 0.7;   ///< of its desired speed: slower yields
inline constexpr double kReactionTime = 0.5;         ///< s of standing or slowing that count
inline constexpr double kEncounterHysteresis = 0.3;  ///< m beyond personal_zone ends it

/// How the pedestrians that came into the robot's personal zone reacted (encounters):
/// encounters = passed + yielded + blocked + standing.
struct CrowdReaction {
  int encounters = 0;
  int passed = 0;            ///< kept at least kYieldSpeedFraction of their desired speed
  int yielded = 0;           ///< slowed below that for kReactionTime, without stopping that long
  int blocked = 0;           ///< stood (below kStopSpeed) for kReactionTime or more: waited
  int standing = 0;          ///< stood still by design (pedestrian mode `stand`): not a reaction
  double wait_time_s = 0.0;  ///< total time the walkers stood during encounters
  double max_wait_s = 0.0;   ///< the longest one walker's encounter stood

  /// Pools another run's reactions into these: counts and waits summed, the longest kept.
  void Add(const CrowdReaction& o) {
    encounters += o.encounters;
    passed += o.passed;
    yielded += o.yielded;
    blocked += o.blocked;
    standing += o.standing;
    wait_time_s += o.wait_time_s;
    max_wait_s = max_wait_s > o.max_wait_s ? max_wait_s : o.max_wait_s;
  }
};

/// The social metrics of the people of one behaviour toward the robot (definitions above).
struct BehaviourSocial {
  int people = 0;                 ///< distinct pedestrians of it met (aggregate: summed over runs)
  double min_gap_m = kMetricNaN;  ///< closest edge-to-edge gap to the robot; NaN: none met
  double intimate_time_s = 0.0;   ///< time with one of them within intimate_zone
  double personal_time_s = 0.0;   ///< time with one of them within personal_zone
  CrowdReaction crowd;
  int runs_stopped = 0;  ///< runs whose stopped_by is this behaviour
};

/// Window (s) at a failed run's end in which stopped_by looks for reacting people.
inline constexpr double kStoppedByWindow = 30.0;

/// Social navigation metrics (definitions at the top of this file).
struct SocialStats {
  double intimate_time_s = 0.0;   ///< time with a pedestrian's edge within intimate_zone
  double personal_time_s = 0.0;   ///< time with a pedestrian's edge within personal_zone
  double min_ttc_s = kMetricNaN;  ///< min time to collision, capped at ttc_horizon; NaN: no samples
  double path_efficiency = kMetricNaN;  ///< taught path length / driven length (successful runs)
  double time_efficiency = kMetricNaN;  ///< taught time / playback time (successful runs)
  Summary jerk_m_s3;                    ///< |d³p/dt³| of the ground-truth position
  CrowdReaction crowd;
  /// Per sim::RobotBehaviour, in its order.
  std::array<BehaviourSocial, core::EnumTraits<sim::RobotBehaviour>::kNames.size()> by_behaviour;
  /// A failed run: the behaviour that stopped it (none: nothing reacting stood in its way).
  std::optional<sim::RobotBehaviour> stopped_by;
};

/// Per-sample series of one run (one entry per PlaybackSample), for metrics and figures.
struct RunSeries {
  std::vector<double> tracking_error_m;        ///< distance to the taught path
  std::vector<double> progress_m;              ///< arc length of the projection on the taught path
  std::vector<double> lateral_offset_m;        ///< signed, > 0 left of the taught path
  std::vector<double> localization_error_m;    ///< NaN where the map index has no teach map
  std::vector<double> localization_error_rad;  ///< NaN where the map index has no teach map
  /// The error's increase from the sample before, in one alignment (ErrorIncrease,
  /// bench/metrics/localizer_health.hpp); NaN at the first sample and across a map switch.
  std::vector<double> error_increase_m;
};

/// The metrics of one playback run.
struct RunMetrics {
  int run = 0;
  std::uint64_t seed = 0;
  Outcome outcome = Outcome::kTimeout;
  bool success = false;
  int samples = 0;
  double time_s = 0.0;
  double path_length_m = 0.0;
  double progress_m = 0.0;
  Summary tracking_error_m;
  Summary localization_error_m;
  Summary localization_error_rad;
  double lost_fraction = kMetricNaN;  ///< of the samples with a localization error
  LocalizerHealth localizer;          ///< the localizer's own account and its estimate's jumps
  CollisionStats collisions;
  std::vector<SwitchError> switches;
  double switch_error_max_m = kMetricNaN;
  double switch_error_max_rad = kMetricNaN;
  DynamicPointStats dynamic_points;
  CpuStats cpu;
  SocialStats social;
};

/// Lateral offsets of the runs at the stations along the taught path.
struct Repeatability {
  double station_spacing_m = 0.0;
  std::vector<int> runs;                       ///< RunTrace.run of each column of offsets_m
  std::vector<double> station_s_m;             ///< arc length of each station
  std::vector<std::vector<double>> offsets_m;  ///< [station][run], NaN: run never crossed it
  std::vector<double> std_m;                   ///< per station, NaN with < 2 runs
  std::vector<double> spread_m;                ///< per station max - min, NaN with < 2 runs
  double repeatability_m = kMetricNaN;
  double max_spread_m = kMetricNaN;
  int stations_used = 0;  ///< stations with >= 2 runs
};

struct SwitchErrorStats {
  int count = 0;  ///< switches with a defined error
  double mean_m = kMetricNaN;
  double max_m = kMetricNaN;
  double mean_rad = kMetricNaN;
  double max_rad = kMetricNaN;
};

/// The metrics over the playback runs of one map mode.
struct AggregateMetrics {
  int runs = 0;
  int successes = 0;
  double success_rate = kMetricNaN;
  std::array<int, 4> outcome_counts{};  ///< indexed by static_cast<int>(Outcome)
  double taught_path_length_m = 0.0;
  double mean_time_s = kMetricNaN;
  double mean_path_length_m = kMetricNaN;
  double mean_progress_m = kMetricNaN;
  Summary tracking_error_m_pooled;
  Summary tracking_error_m_run_mean;
  Summary localization_error_m_pooled;
  Summary localization_error_m_run_mean;
  Summary localization_error_rad_pooled;
  Summary localization_error_rad_run_mean;
  double lost_fraction_pooled = kMetricNaN;
  double lost_fraction_run_mean = kMetricNaN;
  LocalizerHealth localizer;  ///< sums over the runs; the largest jump of any run
  Repeatability repeatability;
  CollisionStats collisions;  ///< totals; minima over all runs
  int runs_with_collision = 0;
  SwitchErrorStats switch_error;
  DynamicPointStats dynamic_points;  ///< totals, ratios of the totals
  CpuStats cpu;                      ///< totals, factor of the totals, updates pooled
  /// Means over runs of the zone times and of the jerk statistics, the minimum time to
  /// collision, the efficiencies' means over successful runs, the crowd's reactions summed (max
  /// wait: the max).
  SocialStats social;
  // Of the taught maps, the same for every run of the mode: set by the experiment
  // (bench/metrics/experiment.hpp), not by Aggregate.
  MapQualityStats map_quality;
  SwitchingQuality switching;
  std::array<int, 5> match_counts{};  ///< scan_matched: keyframe matches by nav::MatchVerdict
};

/// Per-sample tracking, progress, lateral and localization errors of one run.
RunSeries ComputeRunSeries(const TeachTrace& teach, const RunTrace& run,
                           const MetricsConfig& config);

/// The metrics of one run. Never throws for well-formed traces (empty ones included).
RunMetrics ComputeRunMetrics(const TeachTrace& teach, const RunTrace& run,
                             const MetricsConfig& config);

/// The metrics over runs; `metrics[i]` must be ComputeRunMetrics of `runs[i]` (same size).
AggregateMetrics Aggregate(const TeachTrace& teach, const std::vector<RunTrace>& runs,
                           const std::vector<RunMetrics>& metrics, const MetricsConfig& config);

/// The lateral offsets of `runs` at stations along the taught path (part of Aggregate).
Repeatability ComputeRepeatability(const TeachTrace& teach, const std::vector<RunTrace>& runs,
                                   const MetricsConfig& config);

/// repeatability.csv: one row per station — s_m, each run's lateral offset (m; nan where the
/// run never crossed it), the standard deviation and the spread across runs; rounded to 0.1 mm.
void WriteRepeatabilityCsv(const std::filesystem::path& path, const Repeatability& repeatability);

}  // namespace retrace::bench
