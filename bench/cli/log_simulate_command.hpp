#pragma once
// `retrace log-simulate <log> --teach DIR --out FILE.mcap`: the log's reference driven again in
// the simulator, in the consistent map built from it, with the log's LiDAR geometry: the same
// log with simulated scans (bench/replay/log_simulate.hpp), to localize side by side with the
// real one.

#include <filesystem>
#include <string>

#include "bench/cli/log_teach_command.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

struct LogSimulateOptions {
  LogRunOptions run;  ///< `out` is the MCAP file to write; `figures` is not used
  std::filesystem::path teach_dir;
};

void AddLogSimulateOptions(CLI::App* cmd, LogSimulateOptions* options);

/// Writes the simulated log atomically; returns 0. Throws core::Error for bad input, before
/// anything is written.
int RunLogSimulateCommand(const LogSimulateOptions& options);

}  // namespace retrace::bench
