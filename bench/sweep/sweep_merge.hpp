#pragma once
// `retrace merge` as one library call (MergeSweepShards): the results folders of the shards of
// one sweep (`retrace sweep --shard i/N`, run on several machines) joined into one folder that
// is byte-for-byte what the sweep run whole would have written: results.csv sorted by case id,
// timings.csv, sweep.json, and sweep.png. SweepMergeSummary says what it joined. The command
// line and the Python module call these.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/engine/progress.hpp"
#include "bench/sweep/sweep_results.hpp"

namespace retrace::bench {

struct MergeRequest {
  std::vector<std::filesystem::path> inputs;  ///< shard folders
  std::filesystem::path out;
  bool plot = true;  ///< render sweep.png
};

/// The shards joined.
struct SweepMerge {
  std::filesystem::path out;
  std::string name;  ///< the sweep's
  int shards = 0;
  std::size_t cases = 0;
  double wall_time_s = 0.0;
  SweepTableSchema schema;  ///< of results.csv
  std::size_t parameter_count = 0;
  std::vector<SweepRow> rows;  ///< results.csv's, in shard order
};

/// Checks and joins the shards; `command_line` is recorded in sweep.json; a plot that cannot be
/// rendered is a warning to `progress` (may be null). Throws core::Error, before anything is
/// written, when the folders are not the shards 1..N of one sweep exactly once each, a shard is
/// incomplete, a case is missing or duplicated, or `out` holds another sweep.
SweepMerge MergeSweepShards(const MergeRequest& request, const std::string& command_line,
                            ProgressSink* progress);

/// What was joined and the summary table (lines ending in a newline).
std::string SweepMergeSummary(const SweepMerge& merged);

}  // namespace retrace::bench
