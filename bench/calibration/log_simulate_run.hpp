#pragma once
// `retrace log-simulate` as one library call: the log's reference driven again in the simulator,
// in the consistent map built from it, with the log's LiDAR, written as an MCAP file — the same
// log with simulated scans (SimulateLogFile, bench/calibration/log_simulate.hpp) — and what was
// simulated (LogSimulateSummary). The command line and the Python module call these.

#include <cstddef>
#include <filesystem>
#include <string>

#include "bench/calibration/log_simulate.hpp"
#include "bench/replay/log_run_options.hpp"

namespace retrace::bench {

struct LogSimulateRequest {
  LogRunOptions run;                ///< `out` is the MCAP file to write; `figures` is not used
  std::filesystem::path teach_dir;  ///< the consistent map's teach folder: the world
};

/// A simulated log, with what its summary is made of.
struct SimulatedLog {
  LogSimulateRequest request;
  LogSimulation simulation;
  std::size_t beams = 0;         ///< per scan, the log's LiDAR
  std::string reference_source;  ///< what the simulated drive followed
};

/// Reads the teach folder and the log and writes request.run.out (staged beside it as
/// <out>.tmp and renamed when complete: the file is whole or absent). Throws core::Error for bad
/// input, before anything is written.
SimulatedLog SimulateLogFile(const LogSimulateRequest& request);

/// The summary as the command line prints it (two lines, no trailing newline).
std::string LogSimulateSummary(const SimulatedLog& simulated);

}  // namespace retrace::bench
