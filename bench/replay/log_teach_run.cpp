#include "bench/replay/log_teach_run.hpp"

#include <sstream>

#include "bench/engine/switch_points.hpp"
#include "bench/output/manifest.hpp"
#include "bench/output/render_results.hpp"
#include "bench/output/results_io.hpp"
#include "bench/output/staged_folder.hpp"
#include "core/format.hpp"
#include "io/atomic_file.hpp"
#include "io/config_yaml.hpp"
#include "viz/render_error.hpp"

namespace retrace::bench {
namespace {

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

LogManifestInfo TeachManifest(const LogTeaching& taught, MapMode mode,
                              const std::string& command_line, double wall_time_s) {
  const logs::LogIndex& index = taught.index;
  const LogStreams& streams = taught.streams;
  const LogTeachResult& result = taught.result;
  LogManifestInfo manifest;
  manifest.command_line = command_line;
  manifest.fields = LogManifestFields(index, streams, result.first_s, result.last_s);
  manifest.fields.insert(manifest.fields.begin() + 2, {"mode", std::string(core::EnumName(mode))});
  manifest.fields.emplace_back("scans", std::to_string(result.scans));
  manifest.notes = index.notes;
  manifest.config_yaml = io::ConfigToYaml(taught.config);
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

}  // namespace

LogTeaching TeachLog(const LogTeachRequest& request) {
  LogTeaching t;
  t.request = request;
  t.config = LoadLogRunConfig(request.run, request.extra_overrides);
  if (!request.modes.empty()) t.config.modes = request.modes;
  t.index = logs::IndexLog(request.run.log, request.run.streams);
  t.streams =
      PrepareLogStreams(t.index, t.config, request.run.synthetic_odometry, request.run.reference);
  LogTeachModes(t.config, t.streams);  // refuses impossible modes before the drive
  t.result = RunLogTeach(t.index, t.streams, t.config, request.run.window);
  return t;
}

std::vector<std::string> WriteLogTeachFolder(const LogTeaching& taught,
                                             const std::string& command_line, double wall_time_s) {
  StagedFolder folder(taught.request.run.out);
  for (const ModeTeach& teach : taught.result.modes) {
    const std::filesystem::path dir = folder.path() / std::string(core::EnumName(teach.mode));
    WriteTeachFolder(dir / "teach", teach);
    const LogManifestInfo manifest = TeachManifest(taught, teach.mode, command_line, wall_time_s);
    io::WriteFileAtomic(dir / "manifest.yaml", LogManifestYaml(manifest));
  }
  std::vector<std::string> notes;
  if (taught.request.run.figures) notes = RenderTeachFigures(folder.path(), taught.result);
  folder.Commit();
  return notes;
}

std::string LogTeachSummary(const LogTeaching& taught, const std::vector<std::string>& notes) {
  const LogTeachResult& result = taught.result;
  const LogStreams& streams = taught.streams;
  std::ostringstream text;
  text << taught.index.name << ": taught " << core::FixedText(result.last_s - result.first_s, 1)
       << " s of the log (" << core::FixedText(result.first_s, 1) << " to "
       << core::FixedText(result.last_s, 1) << " s), " << result.scans << " scans, "
       << core::FixedText(result.driven_m, 1) << " m driven";
  if (result.scans_outside > 0)
    text << "; " << result.scans_outside << " scans without odometry or reference skipped";
  text << "\n  odometry:  " << streams.odometry_source << "\n  reference: "
       << (streams.reference_source.empty() ? "none" : streams.reference_source) << "\n";
  if (!result.switch_points.empty()) {
    text << "  switch points:";
    for (double s : result.switch_points) text << " " << ArcLengthText(s);
    text << "\n";
  }
  for (const ModeTeach& teach : result.modes) text << "  " << ModeLine(teach) << "\n";
  for (const std::string& note : taught.index.notes) text << "  note: " << note << "\n";
  for (const std::string& note : notes) text << "  " << note << "\n";
  const double log_s = result.last_s - result.first_s;
  text << "teaching: " << core::FixedText(log_s, 1) << " s of log in "
       << core::FixedText(result.cpu_time_s, 2) << " s of CPU ("
       << core::FixedText(result.cpu_time_s > 0 ? log_s / result.cpu_time_s : 0.0, 0)
       << "x real time)\nresults: " << taught.request.run.out.string();
  return text.str();
}

}  // namespace retrace::bench
