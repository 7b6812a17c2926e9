#pragma once
// `retrace crowd-check`: the social-force crowd against measurements. Runs the fundamental
// diagram of a bidirectional ring corridor (bench/crowd/fundamental_diagram.hpp) over a list of
// densities and compares the mean walking speeds with Weidmann's (1993) curve.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

struct CrowdCheckOptions {
  std::filesystem::path out = "results/crowd_check";
  /// Comma-separated densities (persons/m²).
  std::string densities = "0.25,0.5,0.75,1,1.5,2,2.5,3,3.5";
  /// Comma-separated flows (one_way, two_way).
  std::string flows = "one_way,two_way";
  std::uint64_t seed = 1;
  double duration = 0.0;               ///< s of measurement; 0: the config's (40 s)
  double warmup = -1.0;                ///< s; < 0: the config's (20 s)
  std::vector<std::string> overrides;  ///< --set key=value on FundamentalDiagramConfig
};

/// Adds --out, --densities, --flows, --seed, --duration, --warmup and --set to `cmd`.
void AddCrowdCheckOptions(CLI::App* cmd, CrowdCheckOptions* options);

/// Runs the check, writes fundamental_diagram.csv, crowd_check.json and fundamental_diagram.png
/// into options.out and prints the table to stdout. Returns 0 (the check's pass flags are in the
/// table and the JSON, not the exit code). Throws core::ConfigError on bad input (before
/// anything is simulated or written).
int RunCrowdCheckCommand(const CrowdCheckOptions& options);

}  // namespace retrace::bench
