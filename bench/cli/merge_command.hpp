#pragma once
// `retrace merge <shard folder>... --out DIR`: joins the results folders of the shards of one
// sweep (`retrace sweep --shard i/N`, run on several machines) into one folder that is
// byte-for-byte what the sweep run whole would have written: results.csv sorted by case id,
// timings.csv, sweep.json, and sweep.png. One library call (bench/sweep/sweep_merge.hpp).

#include <string>

#include "bench/sweep/sweep_merge.hpp"

namespace CLI {
class App;
}

namespace retrace::bench {

struct MergeOptions {
  MergeRequest request;
};

/// Adds the command's arguments to a CLI11 subcommand.
void AddMergeOptions(CLI::App* command, MergeOptions* options);

/// Checks and joins the shards; prints a summary on stdout. Returns 0. Throws core::Error,
/// before anything is written, when the folders are not the shards 1..N of one sweep exactly
/// once each, a shard is incomplete, a case is missing or duplicated, or `out` holds another
/// sweep.
int RunMergeCommand(const MergeOptions& options, const std::string& command_line);

}  // namespace retrace::bench
