#pragma once
// `retrace sweep` as one library call (RunSweep): the cases of a sweep file run in parallel, one
// row per case appended to <out>/results.csv as each finishes; an interrupted sweep resumes
// where it stopped; one shard of the cases (`i/N`) for a batch scheduler; at the end
// results.csv rewritten sorted by case id and sweep.png plotted. The results do not depend on
// the jobs or on interruptions. SweepRunSummary says what it did. The command line and the
// Python module call these.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/engine/progress.hpp"
#include "bench/sweep/sweep_plan.hpp"
#include "bench/sweep/sweep_results.hpp"
#include "bench/sweep/sweep_spec.hpp"

namespace retrace::bench {

struct SweepRequest {
  std::filesystem::path file;          ///< the sweep file
  int jobs = 0;                        ///< cases at once; 0: one per core
  std::filesystem::path out;           ///< empty: DefaultSweepFolder
  std::string shard;                   ///< "i/N"; empty: all cases
  std::vector<std::string> overrides;  ///< a.b.c=value, applied to every case
  bool plot = true;                    ///< render sweep.png (a whole sweep only)
};

/// A sweep (or shard) done and its folder complete.
struct SweepRun {
  SweepSpec spec;
  SweepShard shard;
  std::filesystem::path out;
  std::size_t shard_cases = 0;  ///< the cases of the shard (all of them, unsharded)
  std::size_t cases_run = 0;    ///< by this call; the others were done before
  double wall_time_s = 0.0;
  std::vector<SweepRow> results;  ///< results.csv, by case id
};

/// Runs the shard's cases that the folder does not hold yet and completes the folder;
/// `command_line` is recorded in sweep.json. Progress (a countdown of the cases) and warnings
/// go to `progress` (may be null). Throws core::Error on bad input (before anything is written:
/// the sweep file, every combination, the shard, a folder holding another sweep) and when a
/// case cannot run (the rows of the finished cases stay).
SweepRun RunSweep(const SweepRequest& request, const std::string& command_line,
                  ProgressSink* progress);

/// What the sweep did and its summary table, or how to join the shards (lines ending in a
/// newline).
std::string SweepRunSummary(const SweepRun& run);

}  // namespace retrace::bench
