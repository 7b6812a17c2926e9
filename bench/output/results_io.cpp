#include "bench/output/results_io.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench/engine/local_truth.hpp"
#include "bench/metrics/metrics_json.hpp"
#include "core/errors.hpp"
#include "io/csv_reader.hpp"
#include "io/csv_writer.hpp"
#include "io/json_writer.hpp"
#include "io/tum.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::bench {
namespace {

nlohmann::json PoseJson(const core::Pose2& X) { return {X.x, X.y, X.theta}; }

std::vector<io::StampedPose> Stamped(const std::vector<double>& time,
                                     const std::vector<core::Pose2>& poses) {
  std::vector<io::StampedPose> out(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) out[i] = {time[i], poses[i]};
  return out;
}

void Unstamp(const std::vector<io::StampedPose>& in, std::vector<double>* time,
             std::vector<core::Pose2>* poses) {
  time->clear();
  poses->clear();
  for (const io::StampedPose& p : in) {
    time->push_back(p.t);
    poses->push_back(p.pose);
  }
}

std::string MapFile(std::size_t k, const char* frame) {
  return "map_" + std::to_string(k) + "_in_" + frame + ".tum";
}

}  // namespace

void WriteSnapshot(const std::filesystem::path& path, const LocalizationSnapshot& s) {
  nlohmann::json particles = nlohmann::json::array();
  for (std::size_t j = 0; j < s.particles.size(); ++j) {
    particles.push_back({s.particles[j].x, s.particles[j].y, s.particles[j].theta, s.weights[j]});
  }
  nlohmann::json pedestrians = nlohmann::json::array();
  for (const sim::DynamicCircle& c : s.pedestrians_W)
    pedestrians.push_back({c.center.x(), c.center.y(), c.radius});
  nlohmann::json j = {{"time_s", s.time},
                      {"map", s.map_index},
                      {"pedestrian_beams", s.pedestrian_beams},
                      {"X_WR", PoseJson(s.X_WR)},
                      {"X_MR_truth", PoseJson(s.X_MR_truth)},
                      {"X_MR_estimate", PoseJson(s.X_MR_estimate)},
                      {"X_RL", PoseJson(s.X_RL)},
                      {"particles", std::move(particles)},
                      {"pedestrians_W", std::move(pedestrians)},
                      {"scan",
                       {{"angle_min", s.scan.angle_min},
                        {"angle_increment", s.scan.angle_increment},
                        {"ranges", s.scan.ranges},
                        {"use", s.beam_use},
                        {"pedestrian", s.pedestrian}}},
                      {"likelihood",
                       {{"origin", {s.likelihood.origin.x(), s.likelihood.origin.y()}},
                        {"resolution", s.likelihood.resolution},
                        {"size", s.likelihood.size},
                        {"theta", s.likelihood.theta},
                        {"all_beams", s.likelihood.all_beams},
                        {"static_beams", s.likelihood.static_beams}}}};
  io::WriteJsonAtomic(path, j);
}

void WriteTeachFolder(const std::filesystem::path& dir, const ModeTeach& teach) {
  nav::WriteTeachBundle(dir, teach.bundle);
  const TeachTrace& trace = teach.trace;
  // Without a truth (a log without reference) there is no gt.tum and no map_<k>_in_world.tum.
  const bool truth = !trace.X_WR.empty();
  if (truth) io::WriteTum(dir / "gt.tum", Stamped(trace.time, trace.X_WR));
  io::WriteTum(dir / "odom.tum", Stamped(trace.time, trace.X_OR));
  for (std::size_t k = 0; k < trace.maps.size(); ++k) {
    const TeachMapTrace& map = trace.maps[k];
    io::WriteTum(dir / "reference" / MapFile(k, "map"), Stamped(map.time, map.X_MR));
    if (truth) io::WriteTum(dir / "reference" / MapFile(k, "world"), Stamped(map.time, map.X_WR));
  }
  // Online switching: where and why the recorder began each map after the first.
  if (!teach.online_switches.empty()) {
    io::CsvWriter switches(dir / "switches.csv",
                           {"map", "odometry_travelled_m", "constraint", "reason"});
    for (std::size_t k = 0; k < teach.online_switches.size(); ++k) {
      const nav::OnlineSwitch& s = teach.online_switches[k];
      switches.AddRow({k + 1, s.travelled, s.constraint, std::string(core::EnumName(s.reason))});
    }
    switches.Commit();
  }
}

std::optional<MapMode> TeachFolderMode(const std::filesystem::path& dir) {
  std::filesystem::path normal = dir.lexically_normal();
  if (normal.filename().empty()) normal = normal.parent_path();
  const std::string parent = normal.parent_path().filename().string();
  for (const auto& [mode, name] : core::EnumTraits<MapMode>::kNames) {
    if (parent == name) return mode;
  }
  return std::nullopt;
}

ModeTeach ReadTeachFolder(const std::filesystem::path& dir, MapMode mode) {
  if (!std::filesystem::is_directory(dir)) {
    throw core::IoError(dir.string() +
                        ": no such teach folder (expected the teach/ folder of a previous run)");
  }
  ModeTeach teach;
  teach.mode = mode;
  teach.bundle = nav::ReadTeachBundle(dir);
  TeachTrace& trace = teach.trace;
  // A log taught without a reference has no gt.tum: no truth to measure against.
  const bool truth = std::filesystem::exists(dir / "gt.tum");
  Unstamp(io::ReadTum(dir / "odom.tum"), &trace.time, &trace.X_OR);
  if (truth) {
    std::vector<double> gt_time;
    Unstamp(io::ReadTum(dir / "gt.tum"), &gt_time, &trace.X_WR);
    if (gt_time != trace.time) {
      throw core::IoError(dir.string() + ": gt.tum and odom.tum must hold the same instants");
    }
  }
  if (trace.time.empty()) throw core::IoError(dir.string() + ": odom.tum holds no pose");
  for (std::size_t k = 0; k < teach.bundle.maps.size(); ++k) {
    TeachMapTrace map;
    Unstamp(io::ReadTum(dir / "reference" / MapFile(k, "map")), &map.time, &map.X_MR);
    std::vector<double> world_time = map.time;
    if (truth)
      Unstamp(io::ReadTum(dir / "reference" / MapFile(k, "world")), &world_time, &map.X_WR);
    if (map.time.empty() || world_time != map.time) {
      throw core::IoError(dir.string() + ": reference/" + MapFile(k, "map") + " and " +
                          MapFile(k, "world") + " must hold the same, non-empty, instants");
    }
    trace.maps.push_back(std::move(map));
  }
  if (std::filesystem::exists(dir / "switches.csv")) {
    const std::vector<io::CsvRecord> rows = io::ReadCsvFile(dir / "switches.csv");
    const auto number = [](const std::string& text, double* value) {
      char* end = nullptr;
      *value = std::strtod(text.c_str(), &end);
      return !text.empty() && end == text.c_str() + text.size();
    };
    for (std::size_t i = 1; i < rows.size(); ++i) {
      const std::vector<std::string>& c = rows[i].cells;
      double travelled = 0.0, constraint = 0.0;
      const std::optional<nav::SwitchReason> reason =
          c.size() == 4 && number(c[1], &travelled) && number(c[2], &constraint)
              ? core::ParseEnum<nav::SwitchReason>(c[3])
              : std::nullopt;
      if (!reason) {
        throw core::IoError((dir / "switches.csv").string() + ":" + std::to_string(rows[i].line) +
                            ": expected map, odometry_travelled_m, constraint, reason (" +
                            core::EnumNameList<nav::SwitchReason>() + ")");
      }
      teach.online_switches.push_back({travelled, constraint, *reason});
    }
  }
  return teach;
}

void WriteEstimateFiles(const std::filesystem::path& dir, const TeachTrace& teach,
                        const std::vector<EstimateRow>& rows, const MetricsConfig& metrics,
                        const std::string& reference_file) {
  io::CsvWriter est_map(dir / "est_map.csv", {"time", "map", "x", "y", "theta"});
  std::vector<io::StampedPose> est, reference;
  std::optional<LocalTruth> local;
  int local_map = -1;
  for (const EstimateRow& r : rows) {
    est_map.AddRow({r.time, r.map, r.X_MR.x, r.X_MR.y, r.X_MR.theta});
    if (!r.X_WR) continue;
    if (r.map != local_map) {
      local.emplace(teach.maps.at(static_cast<std::size_t>(r.map)), metrics.match_window,
                    metrics.match_fallback_distance);
      local_map = r.map;
    }
    local->InMap(*r.X_WR);
    est.push_back({r.time, local->X_WM() * r.X_MR});
    reference.push_back({r.time, *r.X_WR});
  }
  est_map.Commit();
  if (est.empty()) return;
  io::WriteTum(dir / "est.tum", est);
  io::WriteTum(dir / reference_file, reference);
}

std::vector<EventRow> SwitchEvents(const std::vector<SwitchRecord>& switches) {
  std::vector<EventRow> rows;
  for (const SwitchRecord& sw : switches)
    rows.push_back({sw.time, "map_switch", std::to_string(sw.from) + "->" + std::to_string(sw.to)});
  return rows;
}

void WriteEventsCsv(const std::filesystem::path& path, const std::vector<EventRow>& rows) {
  io::CsvWriter events(path, {"time", "event", "detail"});
  for (const EventRow& r : rows) events.AddRow({r.time, r.event, r.detail});
  events.Commit();
}

void WriteRunFolder(const std::filesystem::path& dir, const TeachTrace& teach, const RunTrace& run,
                    const MetricsConfig& metrics) {
  std::vector<EstimateRow> estimates;
  std::vector<io::StampedPose> odom;
  for (const PlaybackSample& s : run.samples) {
    estimates.push_back({s.time, s.map_index, s.X_MR, s.X_WR});
    odom.push_back({s.time, s.X_OR});
  }
  WriteEstimateFiles(dir, teach, estimates, metrics, "gt.tum");
  io::WriteTum(dir / "odom.tum", odom);

  // Merged in time order: switches, collisions and scripted events are each already sorted.
  std::vector<EventRow> rows = SwitchEvents(run.switches);
  for (const sim::CollisionEvent& c : run.collisions) {
    rows.push_back({c.time, "collision",
                    c.kind == sim::CollisionKind::kStatic
                        ? std::string("static")
                        : "pedestrian " + std::to_string(c.pedestrian_id)});
  }
  for (const EventRecord& e : run.events) rows.push_back({e.time, "scripted", e.name});
  for (EventRow& r : OffMapEvents(run.samples)) rows.push_back(std::move(r));
  std::stable_sort(rows.begin(), rows.end(),
                   [](const EventRow& a, const EventRow& b) { return a.time < b.time; });
  rows.push_back({run.sim_time_s, "end", std::string(core::EnumName(run.outcome))});
  WriteEventsCsv(dir / "events.csv", rows);
  if (run.snapshot) WriteSnapshot(dir / "snapshot.json", *run.snapshot);

  // The errors along the route, per control tick, for plots (errors.png) and the user's own.
  const RunSeries series = ComputeRunSeries(teach, run, metrics);
  io::CsvWriter errors(dir / "errors.csv",
                       {"time", "map", "arc_length_m", "lateral_offset_m", "tracking_error_m",
                        "localization_error_m", "localization_error_rad"});
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    errors.AddRow({run.samples[i].time, run.samples[i].map_index, series.progress_m[i],
                   series.lateral_offset_m[i], series.tracking_error_m[i],
                   series.localization_error_m[i], series.localization_error_rad[i]});
  }
  errors.Commit();
}

RunTrace ReadRunFolder(const std::filesystem::path& dir, int run) {
  const std::vector<io::StampedPose> gt = io::ReadTum(dir / "gt.tum");
  const std::vector<io::StampedPose> odom = io::ReadTum(dir / "odom.tum");
  const std::filesystem::path file = dir / "est_map.csv";
  const std::vector<io::CsvRecord> records = io::ReadCsvFile(file);
  const std::vector<std::string> header = {"time", "map", "x", "y", "theta"};
  if (records.empty() || records.front().cells != header) {
    throw core::IoError(file.string() + ":1: expected the header time,map,x,y,theta");
  }
  if (records.size() - 1 != gt.size() || gt.size() != odom.size()) {
    throw core::IoError(dir.string() + ": est_map.csv, gt.tum and odom.tum hold " +
                        std::to_string(records.size() - 1) + ", " + std::to_string(gt.size()) +
                        " and " + std::to_string(odom.size()) + " samples; they must agree");
  }
  RunTrace trace;
  trace.run = run;
  for (std::size_t i = 1; i < records.size(); ++i) {
    const io::CsvRecord& record = records[i];
    const std::string where = file.string() + ":" + std::to_string(record.line) + ": ";
    if (record.cells.size() != header.size()) {
      throw core::IoError(where + "expected 5 cells, found " + std::to_string(record.cells.size()));
    }
    std::array<double, 5> v{};
    for (std::size_t k = 0; k < v.size(); ++k) {
      const std::optional<double> number = io::ParseCsvNumber(record.cells[k]);
      if (!number || !std::isfinite(*number)) {
        throw core::IoError(where + header[k] + " '" + record.cells[k] +
                            "' is not a finite number");
      }
      v[k] = *number;
    }
    if (v[1] < 0 || v[1] != std::floor(v[1])) {
      throw core::IoError(where + "map '" + record.cells[1] + "' is not a map index");
    }
    PlaybackSample s;
    s.time = v[0];
    s.map_index = static_cast<int>(v[1]);
    s.X_MR = core::Pose2(v[2], v[3], v[4]);
    s.X_WR = gt[i - 1].pose;
    s.X_OR = odom[i - 1].pose;
    trace.samples.push_back(s);
  }
  return trace;
}

void WriteModeMetrics(const std::filesystem::path& dir, const ModeResult& result) {
  nlohmann::json metrics;
  metrics["mode"] = std::string(core::EnumName(result.teach.mode));
  metrics["aggregate"] = ToJson(result.aggregate);
  metrics["runs"] = nlohmann::json::array();
  for (const RunMetrics& r : result.run_metrics) metrics["runs"].push_back(ToJson(r));
  io::WriteJsonAtomic(dir / "metrics.json", metrics);
  WriteRepeatabilityCsv(dir / "repeatability.csv", result.aggregate.repeatability);
}

void WriteComparison(const std::filesystem::path& path, const std::vector<ModeResult>& modes) {
  nlohmann::json comparison = nlohmann::json::object();
  for (const ModeResult& mode : modes)
    comparison[std::string(core::EnumName(mode.teach.mode))] = ToJson(mode.aggregate);
  io::WriteJsonAtomic(path, comparison);
}

}  // namespace retrace::bench
