#pragma once
// manifest.yaml: what produced a results folder — the command, the effective scenario config
// (after overrides and the nav copies filled from sim), seed, git revision, build type, library
// versions and wall time — so that any number in it can be reproduced.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

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

/// What made a results folder from a recorded log (`retrace log-teach`, `log-localize`).
struct LogManifestInfo {
  std::string command_line;
  /// Facts in order, key and text: the log, its format, the streams used, the mode, the window.
  std::vector<std::pair<std::string, std::string>> fields;
  std::vector<std::string> notes;
  std::string config_yaml;  ///< the effective config (io::ConfigToYaml)
  double wall_time_s = 0.0;
};

/// The manifest of a log's results folder as YAML text: the facts, then the build (revision,
/// compiler, libraries) as in ManifestYaml, and the config.
std::string LogManifestYaml(const LogManifestInfo& info);

}  // namespace retrace::bench
