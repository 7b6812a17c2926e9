#pragma once
// The files of a run's results folder (docs/DESIGN.md §6):
//
//   <mode>/teach/                 the teach bundle (maps/, paths/, switch_poses.txt, ...) plus
//          gt.tum odom.tum        the teaching drive's ground truth and odometry (TUM, W and O)
//          reference/map_<k>_in_map.tum, map_<k>_in_world.tum
//                                 per partial map, the mapper's pose in M_k and the ground truth
//                                 at the same instants: what local ground truth is made of
//   <mode>/runs/<i>/gt.tum        ground truth X_WR at every control tick
//                  est.tum        the estimate carried into W by the local alignment of the
//                                 nearest teaching sample (so evo's APE against gt.tum is the
//                                 localization error of docs/DESIGN.md §6)
//                  est_map.csv    the raw estimate in its own map: time, map, x, y, theta
//                  odom.tum       wheel odometry X_OR
//                  events.csv     time, event, detail: map switches, collisions, scripted events,
//                                 the outcome
//                  errors.csv     per control tick: time, map, arc length along the taught path,
//                                 signed lateral offset, tracking and localization errors
//                  snapshot.json  see bench/engine/snapshot.hpp
//   <mode>/metrics.json           {"mode", "aggregate", "runs"} (bench/metrics/metrics.hpp)
//   <mode>/repeatability.csv      the lateral offsets of the runs at the stations
//   comparison.json               the aggregates of all modes, when several ran
//
// TUM lines are `t x y z qx qy qz qw` (z = 0, rotation about z), readable by evo.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/engine/snapshot.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/engine/trace.hpp"
#include "bench/metrics/experiment.hpp"
#include "bench/metrics/metrics.hpp"

namespace retrace::bench {

/// Writes snapshot.json (compact arrays; docs/FORMATS.md) atomically.
void WriteSnapshot(const std::filesystem::path& path, const LocalizationSnapshot& snapshot);

/// Writes the teach bundle and the references of one mode into `dir`.
void WriteTeachFolder(const std::filesystem::path& dir, const ModeTeach& teach);

/// The mode of a teach folder `<mode>/teach` (as run, teach and log-teach write them) from its
/// parent folder's name; none when that is not a mode's name.
std::optional<MapMode> TeachFolderMode(const std::filesystem::path& dir);

/// Reads a folder written by WriteTeachFolder (`retrace playback --teach DIR`). Throws
/// core::IoError naming the folder and the missing or malformed file.
ModeTeach ReadTeachFolder(const std::filesystem::path& dir, MapMode mode);

/// One row of est_map.csv and, with a reference, of est.tum and the reference's TUM file.
struct EstimateRow {
  double time = 0.0;
  int map = 0;
  core::Pose2 X_MR;                 ///< the estimate in map `map`
  std::optional<core::Pose2> X_WR;  ///< the ground truth or reference (none: no TUM rows)
};

/// The estimate files of a run, simulated or replayed (docs/FORMATS.md): est_map.csv (every
/// row: time, map, x, y, theta) and, when any row has a reference, est.tum (the estimate carried
/// into W by the local alignment of its map's nearest teaching sample, so that evo's APE against
/// the reference is the localization error) and `reference_file` (the reference).
void WriteEstimateFiles(const std::filesystem::path& dir, const TeachTrace& teach,
                        const std::vector<EstimateRow>& rows, const MetricsConfig& metrics,
                        const std::string& reference_file);

/// One row of events.csv: time, event, detail.
struct EventRow {
  double time = 0.0;
  std::string event, detail;
};
/// The map switches as events.csv rows ("map_switch", "k->l").
std::vector<EventRow> SwitchEvents(const std::vector<SwitchRecord>& switches);
/// "off_map" and "on_map" rows where the stack's off-map flag changes, over samples with `time`
/// and `off_map` members (a simulated run's or a replay's), each flag holding from its time on.
template <class Sample>
std::vector<EventRow> OffMapEvents(const std::vector<Sample>& samples) {
  std::vector<EventRow> rows;
  bool was = false;
  for (const Sample& s : samples) {
    if (s.off_map != was) rows.push_back({s.time, s.off_map ? "off_map" : "on_map", ""});
    was = s.off_map;
  }
  return rows;
}
/// Writes events.csv (the rows as given).
void WriteEventsCsv(const std::filesystem::path& path, const std::vector<EventRow>& rows);

/// Writes one run's trajectories and events into `dir`; `metrics` sets the local-truth matching.
void WriteRunFolder(const std::filesystem::path& dir, const TeachTrace& teach, const RunTrace& run,
                    const MetricsConfig& metrics);

/// Reads back the samples of a folder written by WriteRunFolder (gt.tum, odom.tum and
/// est_map.csv, which must hold the same instants); `run` numbers the trace. Switches,
/// collisions and events are not read. Throws core::IoError naming the file and line.
RunTrace ReadRunFolder(const std::filesystem::path& dir, int run);

/// Writes metrics.json and repeatability.csv of one mode's played-back runs into `dir`.
void WriteModeMetrics(const std::filesystem::path& dir, const ModeResult& result);

/// Writes comparison.json: each mode's aggregate metrics by mode name.
void WriteComparison(const std::filesystem::path& path, const std::vector<ModeResult>& modes);

}  // namespace retrace::bench
