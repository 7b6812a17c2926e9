#pragma once
// manifest.yaml: what produced a results folder — the command, the effective scenario config
// (after overrides and the nav copies filled from sim), seed, git revision, build type, library
// versions and wall time — so that any number in it can be reproduced.

#include <filesystem>
#include <string>

#include "bench/engine/scenario.hpp"
#include "bench/engine/trace.hpp"

namespace retrace::bench {

struct ManifestInfo {
  std::string command_line;
  MapMode mode = MapMode::kPartial;
  double wall_time_s = 0.0;
  std::filesystem::path teach_dir;  ///< set when playback reused an earlier teach folder
};

/// The manifest as YAML text.
std::string ManifestYaml(const Scenario& scenario, const ManifestInfo& info);

/// Writes it atomically. Throws core::IoError.
void WriteManifest(const std::filesystem::path& path, const Scenario& scenario,
                   const ManifestInfo& info);

}  // namespace retrace::bench
