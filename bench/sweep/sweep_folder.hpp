#pragma once
// A sweep's results folder: sweep.json (which sweep and shard it holds, its columns, whether it
// is complete), results.csv and timings.csv (bench/sweep/sweep_results.hpp), sweep.png, and a lock
// so that two processes never write one folder at the same time.
//
// sweep.json:
//   {"format": "retrace sweep 1", "name", "identity" (bench/sweep/sweep_plan.hpp), "shard": "i/N",
//    "sweep_file", "scenario_file", "mode", "repeats", "combinations", "cases" (of the whole
//    sweep), "shard_cases", "cases_done", "complete", "parameters", "labels",
//    "plot_parameters", "metrics",
//    "timing_metrics", "command", "git_revision", "build_type", "wall_time_s" and
//    "cases_run" (of the last command), "merged_from" (retrace merge: the shard folders)}

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/sweep/sweep_plan.hpp"

namespace retrace::bench {

/// The fields of sweep.json that the sweep and merge commands read back.
struct SweepRecord {
  std::string name;
  std::string identity;
  SweepShard shard;
  std::size_t cases = 0;
  std::size_t cases_done = 0;
  bool complete = false;
  std::vector<std::string> parameters;
  std::vector<std::string> plot_parameters;
  std::vector<std::string> metrics;
  std::vector<std::string> timing_metrics;
  nlohmann::json json;  ///< the whole file
};

/// sweep.json of a plan's shard (its run-specific fields are set by the caller).
nlohmann::json SweepJson(const SweepPlan& plan, const SweepShard& shard);

/// Reads sweep.json. Throws core::IoError naming the file when it is missing, not JSON, or
/// lacks a field.
SweepRecord ReadSweepRecord(const std::filesystem::path& file);

/// The default results folder: results/sweeps/<name>, or .../<name>/shard-<i>-of-<N> for a shard.
std::filesystem::path DefaultSweepFolder(const std::string& name, const SweepShard& shard);

/// Renders <folder>/sweep.png from <folder>/results.csv (bench/sweep/sweep_plot.hpp). Returns ""
/// on success, else what went wrong (a core::Error: no off-screen context, say): a missing
/// plot is a warning, never a reason to lose results.
std::string PlotSweepFolder(const std::filesystem::path& folder, const std::string& name,
                            const std::vector<std::string>& parameters,
                            const std::vector<std::string>& metrics);

/// An exclusive lock on a folder (flock on the folder itself, released when the process ends
/// in any way). Throws core::IoError when another process holds it.
class SweepFolderLock {
 public:
  explicit SweepFolderLock(const std::filesystem::path& folder);
  ~SweepFolderLock();
  SweepFolderLock(const SweepFolderLock&) = delete;
  SweepFolderLock& operator=(const SweepFolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace retrace::bench
