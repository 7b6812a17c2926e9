#pragma once
// What an episode records: the teaching drive's ground truth next to each partial map's own
// poses, and per playback run one sample per control tick plus the localizer updates, map
// switches and collisions. The episode runner (bench/engine/playback.cpp) fills these; the metrics
// (bench/metrics/metrics.cpp) are computed from them alone, after the run.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bench/engine/snapshot.hpp"
#include "core/config.hpp"
#include "core/pose2.hpp"
#include "core/twist.hpp"
#include "nav/beam_evidence.hpp"
#include "sim/collision_event.hpp"
#include "sim/pedestrian_behaviour.hpp"

namespace retrace::bench {

/// How the teach bundle's maps were built from the teaching drive.
enum class MapMode {
  kPartial,     ///< odometry maps, a new one at every switch point (the paper's method)
  kSingle,      ///< one odometry map of the whole route
  kConsistent,  ///< one map from ground-truth poses (what a perfect SLAM would give)
  /// partial maps as kPartial, but each keyframe's odometry pose corrected by matching its scan
  /// against the map being built (nav/scan_matcher.hpp): the paper's §5.4 remedy
  kScanMatched,
};

/// Whether a mode starts a new map at every switch point (partial, scan_matched).
inline bool SwitchesMaps(MapMode mode) {
  return mode == MapMode::kPartial || mode == MapMode::kScanMatched;
}

/// One partial map's reference: for every odometry tick of its segment of the teaching drive,
/// the recorder's pose in the map and the ground truth at the same instant.
struct TeachMapTrace {
  std::vector<double> time;       ///< s since the teaching drive started
  std::vector<core::Pose2> X_MR;  ///< X_{M_k R} (the mapper's pose in map k)
  std::vector<core::Pose2> X_WR;  ///< ground truth X_{W R} at the same instant
};

/// The teaching drive as ground truth, and how it maps onto each partial map of one mode.
struct TeachTrace {
  std::vector<double> time;         ///< s, one entry per control tick of the teaching drive
  std::vector<core::Pose2> X_WR;    ///< ground truth (the taught trajectory in W)
  std::vector<core::Pose2> X_OR;    ///< the wheel odometry's own pose
  std::vector<TeachMapTrace> maps;  ///< per partial map of the mode, in order
};

/// One control tick of a playback run.
struct PlaybackSample {
  double time = 0.0;            ///< s since the run started
  int map_index = 0;            ///< the map the localizer works in
  core::Pose2 X_WR;             ///< ground truth
  core::Pose2 X_MR;             ///< the localizer's estimate in map `map_index`
  core::Pose2 X_OR;             ///< wheel odometry
  core::Twist command;          ///< sent to the robot (after avoidance)
  double clearance = 0.0;       ///< m from the robot's edge to the nearest static surface
  double pedestrian_gap = 0.0;  ///< m from the robot's edge to the nearest pedestrian's (inf: none)
  bool avoiding = false;        ///< obstacle avoidance changed the follower's command
  bool lost = false;            ///< the localizer's own verdict (nav::Localizer::lost)
  bool off_map = false;         ///< the stack ran on odometry alone: no map covered the place
};

/// A pedestrian near the robot at one control tick (its edge within kNearbyRange of the robot's),
/// for the social metrics: proxemic zones, time to collision, how the crowd reacts.
struct NearbyPedestrian {
  static constexpr double kNearbyRange = 5.0;  ///< m between the bodies' edges
  int sample = 0;                              ///< index into RunTrace::samples
  int id = 0;                                  ///< the pedestrian (sim DynamicCircle id)
  core::Vec2 position{0, 0};                   ///< W, m
  core::Vec2 velocity{0, 0};                   ///< W, m/s
  double radius = 0.0;                         ///< m
  double desired_speed = 0.0;                  ///< m/s, the speed it walks at when free
  bool standing = false;  ///< stands still by design (pedestrian mode `stand`), never walks
  sim::RobotBehaviour behaviour = sim::RobotBehaviour::kRegular;  ///< toward the robot
  bool reacting = false;  ///< reacting to the robot now (its behaviour's reaction)
};

/// One localizer measurement update that ran, with the dynamic-point test scored against the
/// LiDAR's own knowledge of which beams hit a pedestrian.
struct LocalizerSample {
  double time = 0.0;
  int beams_tested = 0;
  int beams_rejected = 0;
  int true_positive = 0;        ///< rejected and hit a pedestrian
  int false_positive = 0;       ///< rejected, but hit static geometry (or was spurious)
  int false_negative = 0;       ///< tested, hit a pedestrian, not rejected
  double spread = 0.0;          ///< the belief's spread at the endpoints (m, LocalizerUpdate)
  int rejection_particles = 0;  ///< distinct particles in the sums of eq. (9)
  double cpu_s = 0.0;           ///< thread CPU time of the measurement update (s)
  bool reacquired = false;      ///< a recovery trial replaced the belief (LocalizerUpdate)
  bool lost = false;            ///< the localizer counts itself lost after the update
  int beams_used = 0;           ///< beams in the weights
  int trial_updates = 0;        ///< scans the running recovery trial has explained (0: none)
  double trial_log_bayes_factor = 0.0;  ///< its evidence against the belief's (nats)
  nav::BeamEvidence evidence;  ///< the tested beams at the estimate, by class (LocalizerUpdate)
  double reliability = 0.0;    ///< the probability that the estimate is right (LocalizerUpdate)
};

/// A map switch done by the map server.
struct SwitchRecord {
  double time = 0.0;
  int from = 0;
  int to = 0;
  core::Pose2 X_WR;   ///< ground truth at the switch
  core::Pose2 X_MnR;  ///< the estimate in the new map right after the transform (eq. 1)
};

/// A scripted event that fired.
struct EventRecord {
  double time = 0.0;
  std::string name;
};

/// How a playback run ended.
enum class Outcome { kSuccess, kTimeout, kCollision, kLost };

struct RunTrace {
  int run = 0;                ///< index among the repeats
  std::uint64_t seed = 0;     ///< the run's own seed
  double robot_radius = 0.0;  ///< m, the disc the gaps to pedestrians are measured from
  Outcome outcome = Outcome::kTimeout;
  std::vector<PlaybackSample> samples;
  std::vector<NearbyPedestrian> nearby;  ///< by sample, then by pedestrian id
  std::vector<LocalizerSample> updates;
  std::vector<SwitchRecord> switches;
  std::vector<sim::CollisionEvent> collisions;
  std::vector<EventRecord> events;
  /// The update in which the most tested beams hit pedestrians (none if no beam ever did).
  std::optional<LocalizationSnapshot> snapshot;
  double sim_time_s = 0.0;  ///< simulated duration
  double cpu_time_s = 0.0;  ///< thread CPU time of the whole run
};

}  // namespace retrace::bench

template <>
struct retrace::core::EnumTraits<retrace::bench::MapMode> {
  static constexpr std::array<std::pair<retrace::bench::MapMode, std::string_view>, 4> kNames{
      {{retrace::bench::MapMode::kPartial, "partial"},
       {retrace::bench::MapMode::kSingle, "single"},
       {retrace::bench::MapMode::kConsistent, "consistent"},
       {retrace::bench::MapMode::kScanMatched, "scan_matched"}}};
};

template <>
struct retrace::core::EnumTraits<retrace::bench::Outcome> {
  static constexpr std::array<std::pair<retrace::bench::Outcome, std::string_view>, 4> kNames{
      {{retrace::bench::Outcome::kSuccess, "success"},
       {retrace::bench::Outcome::kTimeout, "timeout"},
       {retrace::bench::Outcome::kCollision, "collision"},
       {retrace::bench::Outcome::kLost, "lost"}}};
};
