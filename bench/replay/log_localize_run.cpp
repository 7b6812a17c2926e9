#include "bench/replay/log_localize_run.hpp"

#include <algorithm>
#include <cmath>

#include "bench/engine/local_truth.hpp"
#include "bench/output/manifest.hpp"
#include "bench/output/render_results.hpp"
#include "bench/output/results_io.hpp"
#include "bench/output/staged_folder.hpp"
#include "core/errors.hpp"
#include "core/format.hpp"
#include "io/atomic_file.hpp"
#include "io/config_yaml.hpp"
#include "io/csv_writer.hpp"
#include "io/json_writer.hpp"
#include "viz/figures.hpp"
#include "viz/render_error.hpp"

namespace retrace::bench {
namespace {

// est_map.csv, est.tum and reference.tum, errors.csv, updates.csv, events.csv, snapshot.json.
void WriteRunFiles(const std::filesystem::path& dir, const LogLocalizeResult& run,
                   const LogLocalizeSeries& series, const ModeTeach& teach,
                   const MetricsConfig& metrics) {
  std::vector<EstimateRow> estimates;
  io::CsvWriter errors(dir / "errors.csv", {"time", "map", "driven_m", "path_distance_m",
                                            "localization_error_m", "localization_error_rad"});
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    const LogLocalizeSample& s = run.samples[i];
    // Only where there is local truth can the estimate be carried into the reference's frame.
    estimates.push_back({s.time, s.map, s.X_MR, s.X_WR && s.X_MR_truth ? s.X_WR : std::nullopt});
    errors.AddRow({s.time, s.map, series.driven_m[i], series.path_distance_m[i],
                   series.localization_error_m[i], series.localization_error_rad[i]});
  }
  WriteEstimateFiles(dir, teach.trace, estimates, metrics, "reference.tum");
  errors.Commit();
  io::CsvWriter updates(
      dir / "updates.csv",
      {"time", "beams_tested", "beams_rejected", "spread_m", "rejection_particles", "cpu_ms",
       "lost", "trial_updates", "trial_log_bayes_factor", "reacquired", "explained", "shorter",
       "unknown", "through_wall", "reliability"});
  for (const LocalizerSample& u : run.updates) {
    updates.AddRow({u.time, u.beams_tested, u.beams_rejected, u.spread, u.rejection_particles,
                    u.cpu_s * 1e3, int{u.lost}, u.trial_updates, u.trial_log_bayes_factor,
                    int{u.reacquired}, u.evidence.explained, u.evidence.shorter, u.evidence.unknown,
                    u.evidence.through_wall, u.reliability});
  }
  updates.Commit();
  std::vector<EventRow> events = SwitchEvents(run.switches);
  for (EventRow& r : OffMapEvents(run.samples)) events.push_back(std::move(r));
  std::stable_sort(events.begin(), events.end(),
                   [](const EventRow& a, const EventRow& b) { return a.time < b.time; });
  WriteEventsCsv(dir / "events.csv", events);
  if (run.snapshot) WriteSnapshot(dir / "snapshot.json", *run.snapshot);
}

// snapshot.png and errors.png.
std::vector<std::filesystem::path> RenderFigures(const std::filesystem::path& dir,
                                                 const LogLocalizeResult& run,
                                                 const LogLocalizeSeries& series,
                                                 const ModeTeach& teach, double robot_radius) {
  std::vector<std::filesystem::path> written;
  const std::filesystem::path figures = dir / "figures";
  std::filesystem::create_directories(figures);
  if (run.snapshot) RenderSnapshot(dir / "snapshot.json", teach, robot_radius, figures, &written);
  bool truth = false;
  for (double e : series.localization_error_m) truth = truth || std::isfinite(e);
  if (truth) {
    viz::ErrorsFigureData errors;
    errors.mode = std::string(core::EnumName(teach.mode));
    errors.x_label = "distance driven in the log (m)";
    errors.top_title = "The log's drive: distance to the taught path";
    errors.top_y_label = "distance to the taught path (m)";
    errors.runs.push_back(
        {"log", series.driven_m, series.path_distance_m, series.localization_error_m});
    for (const SwitchRecord& s : run.switches) {
      for (std::size_t i = 0; i < run.samples.size(); ++i) {
        if (run.samples[i].time >= s.time) {
          errors.switch_arc_lengths.push_back(series.driven_m[i]);
          break;
        }
      }
    }
    written.push_back(viz::RenderErrorsFigure(errors, figures / "errors.png").path);
  }
  return written;
}

// The summary lines of a run.
std::string SummaryText(const LogLocalizeMetrics& m, const LogLocalizeResult& run,
                        const std::filesystem::path& out) {
  std::string text = "localized " + core::FixedText(m.duration_s, 1) + " s of the log (" +
                     core::FixedText(run.first_s, 1) + " to " + core::FixedText(run.last_s, 1) +
                     " s): " + std::to_string(m.scans) + " scans, " + std::to_string(m.updates) +
                     " updates, " + std::to_string(m.switches) + " map switches (" +
                     std::to_string(m.maps) + (m.maps == 1 ? " map" : " maps") +
                     (m.loop ? ", a loop" : "") + "), " + std::to_string(m.laps_completed) +
                     (m.laps_completed == 1 ? " lap" : " laps") + " of the taught route\n";
  if (m.has_truth) {
    text += "  localization error: RMS " + core::FixedText(m.localization_error_m.rms, 3) +
            " m, p95 " + core::FixedText(m.localization_error_m.p95, 3) + " m, max " +
            core::FixedText(m.localization_error_m.max, 3) + " m; heading RMS " +
            core::FixedText(m.localization_error_rad.rms * 180.0 / M_PI, 2) + " deg; above " +
            "metrics.lost_error " + core::FixedText(100.0 * m.lost_fraction, 1) + " % of scans\n";
    text += "  on the taught route (within " + core::FixedText(kOnRoute, 1) + " m of it, " +
            core::FixedText(100.0 * m.on_route_fraction, 1) + " % of scans): RMS " +
            core::FixedText(m.localization_error_on_route_m.rms, 3) + " m, p95 " +
            core::FixedText(m.localization_error_on_route_m.p95, 3) + " m, max " +
            core::FixedText(m.localization_error_on_route_m.max, 3) + " m\n";
    text += "  the drive's distance to the taught path: mean " +
            core::FixedText(m.path_distance_m.mean, 2) + " m, max " +
            core::FixedText(m.path_distance_m.max, 2) + " m\n";
  } else {
    text +=
        "  no reference: no localization error (give --reference FILE, or "
        "--synthetic-odometry on a corrected log)\n";
  }
  const LocalizerHealth& h = m.localizer;
  text += "  the localizer: lost (by its own account) " + core::FixedText(h.lost_time_s, 1) +
          " s in " + std::to_string(h.lost_spells) + (h.lost_spells == 1 ? " spell" : " spells") +
          ", " + std::to_string(h.reacquisitions) +
          " re-acquisitions; largest single-update jump " + core::FixedText(h.max_jump_m, 2) +
          " m (at " + core::FixedText(h.max_jump_time_s, 1) + " s); off map (odometry only) " +
          core::FixedText(h.off_map_time_s, 1) + " s\n";
  if (m.has_truth) {
    text += "  against the reference: " + std::to_string(h.reacquisitions_closer) +
            " re-acquisitions brought the estimate closer, " +
            std::to_string(h.reacquisitions_wrong) +
            " took it more than 0.5 m farther; largest single-update error increase " +
            core::FixedText(h.max_error_increase_m, 2) + " m (at " +
            core::FixedText(h.max_error_increase_time_s, 1) + " s); " + std::to_string(m.switches) +
            " map switches, " + std::to_string(h.wrong_switches) +
            " into a map whose taught path the reference was not on\n"
            "  silent failure (error above 1 m, not lost, not off map) " +
            core::FixedText(h.silent_failure_time_s, 1) + " s, longest " +
            core::FixedText(h.longest_silent_failure_s, 1) +
            " s; false alarm (lost, error below 0.3 m) " +
            core::FixedText(h.false_alarm_time_s, 1) + " s\n";
  }
  text += "  beams rejected as dynamic: " + core::FixedText(100.0 * m.rejected_fraction, 2) +
          " %; update time mean " + core::FixedText(m.update_time_ms.mean, 2) + " ms, p95 " +
          core::FixedText(m.update_time_ms.p95, 2) + " ms; " +
          core::FixedText(m.real_time_factor, 0) + "x real time\nresults: " + out.string();
  return text;
}

// The manifest of a localization run: what was localized in what, and its notes and warnings.
LogManifestInfo LocalizeManifest(const LogLocalizeRequest& options, const std::string& command_line,
                                 const logs::LogIndex& index, const LogStreams& streams,
                                 const LogLocalizeResult& run, const LogLocalizeSeries& series,
                                 const ModeTeach& teach) {
  LogManifestInfo manifest;
  manifest.command_line = command_line;
  manifest.fields = LogManifestFields(index, streams, run.first_s, run.last_s);
  manifest.fields.insert(
      manifest.fields.begin() + 2,
      {{"teach", options.teach_dir.string()}, {"mode", std::string(core::EnumName(teach.mode))}});
  manifest.notes = index.notes;
  if (const std::string off_route = OffRouteWarning(series); !off_route.empty())
    manifest.notes.push_back("warning: " + off_route);
  if (!streams.reference.empty() && teach.trace.X_WR.empty()) {
    manifest.notes.push_back(
        "the teach folder has no reference (gt.tum): no local truth, so no "
        "localization error");
  }
  return manifest;
}

}  // namespace

LogLocalization LocalizeLog(const LogLocalizeRequest& request) {
  LogLocalization l;
  l.request = request;
  l.config = LoadLogRunConfig(request.run, {});
  LogReplayOptions replay;
  replay.initial = request.initial;
  replay.every_odometry_tick = request.every_odometry_tick;
  l.teach = ReadTeachFolder(request.teach_dir,
                            TeachFolderMode(request.teach_dir).value_or(MapMode::kPartial));
  l.index = logs::IndexLog(request.run.log, request.run.streams);
  l.streams =
      PrepareLogStreams(l.index, l.config, request.run.synthetic_odometry, request.run.reference);
  l.run = RunLogLocalize(l.index, l.streams, l.teach, l.config, request.run.window, replay);
  l.series = ComputeLogSeries(l.run, l.teach.trace);
  l.metrics = ComputeLogMetrics(l.run, l.series, l.teach.bundle, l.teach.trace, l.config.metrics);
  return l;
}

std::vector<std::string> WriteLogLocalizeFolder(const LogLocalization& l,
                                                const std::string& command_line,
                                                double wall_time_s) {
  const LogLocalizeRequest& request = l.request;
  StagedFolder folder(request.run.out);
  WriteRunFiles(folder.path(), l.run, l.series, l.teach, l.config.metrics);
  nlohmann::json j = ToJson(l.metrics);
  j["log"] = l.index.name;
  j["teach"] = request.teach_dir.string();
  io::WriteJsonAtomic(folder.path() / "metrics.json", j);
  LogManifestInfo manifest =
      LocalizeManifest(request, command_line, l.index, l.streams, l.run, l.series, l.teach);
  manifest.config_yaml = io::ConfigToYaml(l.config);
  manifest.wall_time_s = wall_time_s;
  io::WriteFileAtomic(folder.path() / "manifest.yaml", LogManifestYaml(manifest));
  std::vector<std::string> notes = manifest.notes;
  if (request.run.figures) {
    try {
      RenderFigures(folder.path(), l.run, l.series, l.teach, l.streams.robot.radius);
    } catch (const viz::RenderError& e) {
      notes.push_back(std::string("figures not rendered: ") + e.what());
    }
  }
  folder.Commit();
  return notes;
}

std::string LogLocalizeSummary(const LogLocalization& l) {
  return l.index.name + ": " + SummaryText(l.metrics, l.run, l.request.run.out);
}

}  // namespace retrace::bench
