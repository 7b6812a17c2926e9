#pragma once
// `retrace crowd-check` as library calls: the fundamental diagram of a ring corridor
// (fundamental_diagram.hpp) in one-way and two-way flow over a list of densities, its results
// folder (fundamental_diagram.csv, crowd_check.json, fundamental_diagram.png; docs/CLI.md) and
// the table the command prints.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "bench/crowd/fundamental_diagram.hpp"

namespace retrace::bench {

struct CrowdCheckRequest {
  std::vector<double> densities;  ///< persons/m² (ParseDensityList)
  /// The flows to run, each over every density (ParseFlowList).
  std::vector<CrowdFlow> flows{CrowdFlow::kOneWay, CrowdFlow::kTwoWay};
  std::uint64_t seed = 1;              ///< of the start points and desired speeds
  double duration = 0.0;               ///< s of measurement; 0: the config's (40 s)
  double warmup = -1.0;                ///< s; < 0: the config's (20 s)
  std::vector<std::string> overrides;  ///< key=value on FundamentalDiagramConfig
};

struct CrowdCheck {
  FundamentalDiagramConfig config;
  std::vector<FundamentalDiagramResult> flows;  ///< one per requested flow, in its order
  std::vector<double> flow_seconds;             ///< wall time of each flow's simulation (s)
  double seconds = 0.0;                         ///< wall time of the whole simulation
  bool pass = false;                            ///< every flow passes
};

/// "0.25, 1,2" → {0.25, 1, 2}. Throws core::ConfigError("densities") on a word that is not a
/// number or a density outside (0, Weidmann's jam density).
std::vector<double> ParseDensityList(const std::string& text);

/// "one_way, two_way" → {kOneWay, kTwoWay}. Throws core::ConfigError("flows") on an unknown word,
/// a repeated one or an empty list.
std::vector<CrowdFlow> ParseFlowList(const std::string& text);

/// Runs every flow at every density, one after the other; `progress` (may be empty) hears of
/// each finished density with the number finished so far. Throws core::ConfigError naming a bad
/// key.
CrowdCheck RunCrowdCheck(
    const CrowdCheckRequest& request,
    const std::function<void(const FundamentalDiagramRow& row, std::size_t done)>& progress);

/// Writes the results folder `out` (created when missing).
void WriteCrowdCheckFolder(const std::filesystem::path& out, const CrowdCheck& check,
                           const CrowdCheckRequest& request);

/// The table of speeds against Weidmann's, the verdicts and what was simulated where.
std::string CrowdCheckSummary(const CrowdCheck& check, const std::filesystem::path& out);

}  // namespace retrace::bench
