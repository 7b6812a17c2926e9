#pragma once
// `retrace log-simulate <log> --teach DIR --out FILE.mcap`: the options of
// bench/calibration/log_simulate_run.hpp's SimulateLogFile, which it calls: the log's reference
// driven again in the simulator, in the consistent map built from it, with the log's LiDAR
// geometry — the same log with simulated scans, to localize side by side with the real one;
// prints its summary.

#include "bench/calibration/log_simulate_run.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

struct LogSimulateOptions {
  LogSimulateRequest request;
};

void AddLogSimulateOptions(CLI::App* cmd, LogSimulateOptions* options);

/// Writes the simulated log atomically; returns 0. Throws core::Error for bad input, before
/// anything is written.
int RunLogSimulateCommand(const LogSimulateOptions& options);

}  // namespace retrace::bench
