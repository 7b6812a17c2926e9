#include "bench/cli/log_teach_command.hpp"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/log_options.hpp"
#include "bench/cli/mode_list.hpp"
#include "bench/cli/shared_options.hpp"
#include "bench/engine/switch_points.hpp"
#include "bench/output/manifest.hpp"
#include "bench/output/render_results.hpp"
#include "bench/output/results_io.hpp"
#include "bench/output/staged_folder.hpp"
#include "core/errors.hpp"
#include "core/format.hpp"
#include "io/atomic_file.hpp"
#include "io/config_override.hpp"
#include "io/config_yaml.hpp"
#include "viz/render_error.hpp"

namespace retrace::bench {

namespace {

// --switch-points auto|online|s1,s2,... as the key route.switch_points.
std::string SwitchPointsOverride(const std::string& text) {
  if (text == "auto" || text == "online") return "route.switch_points=" + text;
  return "route.switch_points=[" + text + "]";
}

std::string ModeLine(const ModeTeach& teach) {
  std::string line = std::string(core::EnumName(teach.mode)) + ": " +
                     std::to_string(teach.bundle.maps.size()) +
                     (teach.bundle.maps.size() == 1 ? " map" : " maps");
  if (!teach.online_switches.empty()) {
    line += ", switched online after";
    for (std::size_t i = 0; i < teach.online_switches.size(); ++i) {
      const nav::OnlineSwitch& s = teach.online_switches[i];
      line += (i ? ", " : " ") + core::FixedText(s.travelled, 1) + " m (" +
              std::string(core::EnumName(s.reason)) + ")";
    }
    line += " of odometry";
  }
  if (teach.mode == MapMode::kScanMatched) {
    const auto& c = teach.match_counts;
    int total = 0;
    for (int n : c) total += n;
    line += "; keyframes matched " + std::to_string(c[0]) + " of " + std::to_string(total) +
            " (degenerate " + std::to_string(c[3]) + ", poor fit " + std::to_string(c[4]) +
            ", few points " + std::to_string(c[2]) + ", map start " + std::to_string(c[1]) + ")";
  }
  return line;
}

LogManifestInfo TeachManifest(const logs::LogIndex& index, const LogStreams& streams,
                              const LogTeachResult& result, MapMode mode, const LogConfig& config,
                              const std::string& command_line, double wall_time_s) {
  LogManifestInfo manifest;
  manifest.command_line = command_line;
  manifest.fields = {
      {"log", index.name},
      {"log_format", std::string(logs::LogFormatName(index.format))},
      {"mode", std::string(core::EnumName(mode))},
      {"scan_topic", index.scan_topic},
      {"odometry", streams.odometry_source},
      {"reference", streams.reference_source.empty() ? "none" : streams.reference_source},
      {"lidar_mount", index.mount_source},
      {"from_s", core::FormatNumber(result.first_s)},
      {"to_s", core::FormatNumber(result.last_s)},
      {"scans", std::to_string(result.scans)}};
  manifest.notes = index.notes;
  manifest.config_yaml = io::ConfigToYaml(config);
  manifest.wall_time_s = wall_time_s;
  return manifest;
}

// Returns the notes to print: a figure that cannot be rendered does not fail the teach.
std::vector<std::string> RenderTeachFigures(const std::filesystem::path& folder,
                                            const LogTeachResult& result) {
  std::vector<std::string> notes;
  try {
    for (const ModeTeach& teach : result.modes) {
      const std::filesystem::path figures =
          folder / std::string(core::EnumName(teach.mode)) / "figures";
      std::filesystem::create_directories(figures);
      RenderTeachMaps(teach, {}, figures / "maps.png", viz::RouteSource::kReference);
    }
  } catch (const viz::RenderError& e) {
    notes.push_back(std::string("figures not rendered: ") + e.what());
  }
  return notes;
}

void PrintTeachSummary(const logs::LogIndex& index, const LogStreams& streams,
                       const LogTeachResult& result, const std::vector<std::string>& figure_notes) {
  std::cout << index.name << ": taught " << core::FixedText(result.last_s - result.first_s, 1)
            << " s of the log (" << core::FixedText(result.first_s, 1) << " to "
            << core::FixedText(result.last_s, 1) << " s), " << result.scans << " scans, "
            << core::FixedText(result.driven_m, 1) << " m driven";
  if (result.scans_outside > 0)
    std::cout << "; " << result.scans_outside << " scans without odometry or reference skipped";
  std::cout << "\n  odometry:  " << streams.odometry_source << "\n  reference: "
            << (streams.reference_source.empty() ? "none" : streams.reference_source) << "\n";
  if (!result.switch_points.empty()) {
    std::cout << "  switch points:";
    for (double s : result.switch_points) std::cout << " " << ArcLengthText(s);
    std::cout << "\n";
  }
  for (const ModeTeach& teach : result.modes) std::cout << "  " << ModeLine(teach) << "\n";
  for (const std::string& note : index.notes) std::cout << "  note: " << note << "\n";
  for (const std::string& note : figure_notes) std::cout << "  " << note << "\n";
  const double log_s = result.last_s - result.first_s;
  std::cout << "teaching: " << core::FixedText(log_s, 1) << " s of log in "
            << core::FixedText(result.cpu_time_s, 2) << " s of CPU ("
            << core::FixedText(result.cpu_time_s > 0 ? log_s / result.cpu_time_s : 0.0, 0)
            << "x real time)\n";
}

}  // namespace

void AddLogRunOptions(CLI::App* cmd, LogRunOptions* options) {
  AddLogArgument(cmd, &options->log);
  AddOutOption(cmd, &options->out, "Results folder to write")->required();
  AddWindowOptions(cmd, &options->window);
  cmd->add_flag("--synthetic-odometry", options->synthetic_odometry,
                "Draw drifting odometry from the reference (or from the log's odometry, which "
                "then becomes the reference) with the simulator's model: sim.odometry, seed");
  AddReferenceOption(cmd, &options->reference);
  AddConfigOption(cmd, &options->config,
                  "Settings file (YAML): seed, modes, route, sim.odometry, nav, playback, metrics");
  AddSetOption(cmd, &options->overrides, "a setting: a.b.c=value");
  AddSeedOption(cmd, &options->seed, "of the synthetic odometry and the localizer");
  AddNoFiguresFlag(cmd, &options->figures);
  AddStreamOptions(cmd, &options->streams);
}

void AddLogTeachOptions(CLI::App* cmd, LogTeachOptions* options) {
  AddLogRunOptions(cmd, &options->run);
  cmd->add_option("--switch-points", options->switch_points,
                  "Where maps switch: online (the recorder decides), auto (from the driven "
                  "path) or arc lengths along it, s1,s2,... (m); default online");
  cmd->add_option("--mode", options->modes,
                  "Map modes: partial|single|consistent|scan_matched, comma-separated (default: "
                  "partial, scan_matched and, with a reference, consistent)")
      ->delimiter(',');
}

int RunLogTeachCommand(const LogTeachOptions& options, const std::string& command_line) {
  const auto wall_start = std::chrono::steady_clock::now();
  std::vector<std::string> extra;
  if (!options.switch_points.empty()) extra.push_back(SwitchPointsOverride(options.switch_points));
  LogConfig config = LoadLogRunConfig(options.run, extra);
  if (!options.modes.empty()) config.modes = ParseModeList(options.modes, "--mode");

  const logs::LogIndex index = logs::IndexLog(options.run.log, options.run.streams);
  const LogStreams streams =
      PrepareLogStreams(index, config, options.run.synthetic_odometry, options.run.reference);
  LogTeachModes(config, streams);  // refuses impossible modes before the drive
  const LogTeachResult result = RunLogTeach(index, streams, config, options.run.window);

  StagedFolder folder(options.run.out);
  const double wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  for (const ModeTeach& teach : result.modes) {
    const std::filesystem::path dir = folder.path() / std::string(core::EnumName(teach.mode));
    WriteTeachFolder(dir / "teach", teach);
    const LogManifestInfo manifest =
        TeachManifest(index, streams, result, teach.mode, config, command_line, wall_time_s);
    io::WriteFileAtomic(dir / "manifest.yaml", LogManifestYaml(manifest));
  }
  std::vector<std::string> figure_notes;
  if (options.run.figures) figure_notes = RenderTeachFigures(folder.path(), result);
  folder.Commit();

  PrintTeachSummary(index, streams, result, figure_notes);
  std::cout << "results: " << options.run.out.string() << "\n";
  return 0;
}

}  // namespace retrace::bench
