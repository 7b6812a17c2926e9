#include "bench/cli/log_localize_command.hpp"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "bench/cli/log_options.hpp"
#include "bench/engine/local_truth.hpp"
#include "bench/output/manifest.hpp"
#include "bench/output/render_results.hpp"
#include "bench/output/results_io.hpp"
#include "bench/output/staged_folder.hpp"
#include "bench/replay/log_metrics.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/config_yaml.hpp"
#include "io/csv_writer.hpp"
#include "io/json_writer.hpp"
#include "viz/figures.hpp"
#include "viz/render_error.hpp"

namespace retrace::bench {

namespace {

// "x,y,yaw_deg" → a pose in map 0.
core::Pose2 ParseInitialPose(const std::string& text) {
  double x = 0.0, y = 0.0, yaw_deg = 0.0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &x, &y, &yaw_deg, &tail) != 3 ||
      !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(yaw_deg)) {
    throw core::ConfigError("--initial-pose",
                            "must be x,y,yaw_deg (m, m, degrees in map 0), got '" + text + "'");
  }
  return {x, y, core::DegToRad(yaw_deg)};
}

void WriteRunFiles(const std::filesystem::path& dir, const LogLocalizeResult& run,
                   const LogLocalizeSeries& series, const ModeTeach& teach,
                   const MetricsConfig& metrics) {
  io::CsvWriter est_map(dir / "est_map.csv", {"time", "map", "x", "y", "theta"});
  io::CsvWriter errors(dir / "errors.csv", {"time", "map", "driven_m", "path_distance_m",
                                            "localization_error_m", "localization_error_rad"});
  std::vector<io::StampedPose> est, reference;
  std::optional<LocalTruth> local;
  int local_map = -1;
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    const LogLocalizeSample& s = run.samples[i];
    est_map.AddRow({s.time, s.map, s.X_MR.x, s.X_MR.y, s.X_MR.theta});
    errors.AddRow({s.time, s.map, series.driven_m[i], series.path_distance_m[i],
                   series.localization_error_m[i], series.localization_error_rad[i]});
    if (s.X_WR && s.X_MR_truth) {
      // The estimate carried into the reference's frame through the local alignment, so that
      // evo's APE of est.tum against reference.tum is the localization error.
      if (s.map != local_map) {
        local.emplace(teach.trace.maps.at(static_cast<std::size_t>(s.map)), metrics.match_window,
                      metrics.match_fallback_distance);
        local_map = s.map;
      }
      local->InMap(*s.X_WR);
      est.push_back({s.time, local->X_WM() * s.X_MR});
      reference.push_back({s.time, *s.X_WR});
    }
  }
  est_map.Commit();
  errors.Commit();
  if (!est.empty()) {
    io::WriteTum(dir / "est.tum", est);
    io::WriteTum(dir / "reference.tum", reference);
  }
  io::CsvWriter updates(
      dir / "updates.csv",
      {"time", "beams_tested", "beams_rejected", "spread_m", "rejection_particles", "cpu_ms",
       "lost", "trial_updates", "trial_log_bayes_factor", "reacquired"});
  for (const LocalizerSample& u : run.updates) {
    updates.AddRow({u.time, u.beams_tested, u.beams_rejected, u.spread, u.rejection_particles,
                    u.cpu_s * 1e3, int{u.lost}, u.trial_updates, u.trial_log_bayes_factor,
                    int{u.reacquired}});
  }
  updates.Commit();
  io::CsvWriter events(dir / "events.csv", {"time", "event", "detail"});
  for (const SwitchRecord& s : run.switches) {
    events.AddRow(
        {s.time, std::string("map_switch"), std::to_string(s.from) + "->" + std::to_string(s.to)});
  }
  events.Commit();
  if (run.snapshot) WriteSnapshot(dir / "snapshot.json", *run.snapshot);
}

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

std::string SummaryText(const LogLocalizeMetrics& m, const LogLocalizeResult& run,
                        const std::filesystem::path& out) {
  std::string text = "localized " + FixedText(m.duration_s, 1) + " s of the log (" +
                     FixedText(run.first_s, 1) + " to " + FixedText(run.last_s, 1) +
                     " s): " + std::to_string(m.scans) + " scans, " + std::to_string(m.updates) +
                     " updates, " + std::to_string(m.switches) + " map switches (" +
                     std::to_string(m.maps) + (m.maps == 1 ? " map" : " maps") +
                     (m.loop ? ", a loop" : "") + "), " + std::to_string(m.laps_completed) +
                     (m.laps_completed == 1 ? " lap" : " laps") + " of the taught route\n";
  if (m.has_truth) {
    text += "  localization error: RMS " + FixedText(m.localization_error_m.rms, 3) + " m, p95 " +
            FixedText(m.localization_error_m.p95, 3) + " m, max " +
            FixedText(m.localization_error_m.max, 3) + " m; heading RMS " +
            FixedText(m.localization_error_rad.rms * 180.0 / M_PI, 2) + " deg; above " +
            "metrics.lost_error " + FixedText(100.0 * m.lost_fraction, 1) + " % of scans\n";
    text += "  on the taught route (within " + FixedText(kOnRoute, 1) + " m of it, " +
            FixedText(100.0 * m.on_route_fraction, 1) + " % of scans): RMS " +
            FixedText(m.localization_error_on_route_m.rms, 3) + " m, p95 " +
            FixedText(m.localization_error_on_route_m.p95, 3) + " m, max " +
            FixedText(m.localization_error_on_route_m.max, 3) + " m\n";
    text += "  the drive's distance to the taught path: mean " +
            FixedText(m.path_distance_m.mean, 2) + " m, max " +
            FixedText(m.path_distance_m.max, 2) + " m\n";
  } else {
    text +=
        "  no reference: no localization error (give --reference FILE, or "
        "--synthetic-odometry on a corrected log)\n";
  }
  const LocalizerHealth& h = m.localizer;
  text += "  the localizer: lost (by its own account) " + FixedText(h.lost_time_s, 1) + " s in " +
          std::to_string(h.lost_spells) + (h.lost_spells == 1 ? " spell" : " spells") + ", " +
          std::to_string(h.reacquisitions) + " re-acquisitions; largest single-update jump " +
          FixedText(h.max_jump_m, 2) + " m (at " + FixedText(h.max_jump_time_s, 1) + " s)\n";
  if (m.has_truth) {
    text += "  against the reference: " + std::to_string(h.reacquisitions_closer) +
            " re-acquisitions brought the estimate closer, " +
            std::to_string(h.reacquisitions_wrong) +
            " took it more than 0.5 m farther; largest single-update error increase " +
            FixedText(h.max_error_increase_m, 2) + " m (at " +
            FixedText(h.max_error_increase_time_s, 1) + " s)\n";
  }
  text += "  beams rejected as dynamic: " + FixedText(100.0 * m.rejected_fraction, 2) +
          " %; update time mean " + FixedText(m.update_time_ms.mean, 2) + " ms, p95 " +
          FixedText(m.update_time_ms.p95, 2) + " ms; " + FixedText(m.real_time_factor, 0) +
          "x real time\nresults: " + out.string();
  return text;
}

// The manifest of a localization run: what was localized in what, and its notes and warnings.
LogManifestInfo LocalizeManifest(const LogLocalizeOptions& options, const std::string& command_line,
                                 const logs::LogIndex& index, const LogStreams& streams,
                                 const LogLocalizeResult& run, const LogLocalizeSeries& series,
                                 const ModeTeach& teach) {
  LogManifestInfo manifest;
  manifest.command_line = command_line;
  manifest.fields = {
      {"log", index.name},
      {"log_format", std::string(logs::LogFormatName(index.format))},
      {"teach", options.teach_dir.string()},
      {"mode", std::string(core::EnumName(teach.mode))},
      {"scan_topic", index.scan_topic},
      {"odometry", streams.odometry_source},
      {"reference", streams.reference_source.empty() ? "none" : streams.reference_source},
      {"lidar_mount", index.mount_source},
      {"from_s", core::FormatNumber(run.first_s)},
      {"to_s", core::FormatNumber(run.last_s)}};
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

void AddLogLocalizeOptions(CLI::App* cmd, LogLocalizeOptions* options) {
  AddLogRunOptions(cmd, &options->run);
  cmd->add_option("--teach", options->teach_dir,
                  "The teach/ folder to localize in (<mode>/teach of log-teach or run)")
      ->required();
  cmd->add_option("--initial-pose", options->initial_pose,
                  "Where the robot starts, in map 0's frame: x,y,yaw_deg; it starts in the map "
                  "whose taught path is nearest (default: the map nearest the reference when "
                  "there is one, else map 0's origin)");
  cmd->add_flag("--every-odometry-tick", options->every_odometry_tick,
                "One prediction per odometry message, as the simulator's playback predicts "
                "(default: the fewest arcs that follow the messages within 1 mm)");
}

int RunLogLocalizeCommand(const LogLocalizeOptions& options, const std::string& command_line) {
  const auto wall_start = std::chrono::steady_clock::now();
  const LogConfig config = LoadLogRunConfig(options.run, {});
  LogReplayOptions replay;
  if (!options.initial_pose.empty()) replay.initial = ParseInitialPose(options.initial_pose);
  replay.every_odometry_tick = options.every_odometry_tick;
  const ModeTeach teach = ReadTeachFolder(
      options.teach_dir, TeachFolderMode(options.teach_dir).value_or(MapMode::kPartial));
  const logs::LogIndex index = logs::IndexLog(options.run.log, options.run.streams);
  const LogStreams streams =
      PrepareLogStreams(index, config, options.run.synthetic_odometry, options.run.reference);
  const LogLocalizeResult run =
      RunLogLocalize(index, streams, teach, config, options.run.window, replay);
  const LogLocalizeSeries series = ComputeLogSeries(run, teach.trace);
  const LogLocalizeMetrics metrics = ComputeLogMetrics(run, series, teach.bundle, config.metrics);

  StagedFolder folder(options.run.out);
  WriteRunFiles(folder.path(), run, series, teach, config.metrics);
  nlohmann::json j = ToJson(metrics);
  j["log"] = index.name;
  j["teach"] = options.teach_dir.string();
  io::WriteJsonAtomic(folder.path() / "metrics.json", j);
  LogManifestInfo manifest =
      LocalizeManifest(options, command_line, index, streams, run, series, teach);
  manifest.config_yaml = io::ConfigToYaml(config);
  manifest.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  io::WriteFileAtomic(folder.path() / "manifest.yaml", LogManifestYaml(manifest));
  std::string figure_note;
  if (options.run.figures) {
    try {
      RenderFigures(folder.path(), run, series, teach, streams.robot.radius);
    } catch (const viz::RenderError& e) {
      figure_note = std::string("\n  figures not rendered: ") + e.what();
    }
  }
  folder.Commit();
  std::cout << index.name << ": " << SummaryText(metrics, run, options.run.out) << figure_note
            << "\n";
  for (const std::string& note : manifest.notes)
    std::cout << "  " << (note.starts_with("warning: ") ? "" : "note: ") << note << "\n";
  return 0;
}

}  // namespace retrace::bench
