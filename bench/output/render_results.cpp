#include "bench/output/render_results.hpp"

#include <yaml-cpp/yaml.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/engine/local_truth.hpp"
#include "bench/metrics/metrics.hpp"
#include "bench/output/results_io.hpp"
#include "bench/output/world_shapes.hpp"
#include "core/errors.hpp"
#include "io/config_yaml.hpp"
#include "io/json_writer.hpp"
#include "io/tum.hpp"
#include "sim/world_file.hpp"
#include "viz/figure_data.hpp"
#include "viz/figures.hpp"

namespace retrace::bench {
namespace {

// What a mode's figures need from the run that wrote it, as its manifest records it: the world
// (the scenario's world file), the robot's radius and the metrics' settings.
struct RunSetup {
  sim::World world;
  double robot_radius = 0.0;
  MetricsConfig metrics;
};

RunSetup ReadRunSetup(const std::filesystem::path& mode_dir) {
  const std::filesystem::path manifest = mode_dir / "manifest.yaml";
  YAML::Node node;
  try {
    node = YAML::LoadFile(manifest.string());
  } catch (const YAML::Exception& e) {
    throw core::IoError(manifest.string() + ": cannot read the manifest (" + e.what() + ")");
  }
  const std::filesystem::path scenario = node["scenario_file"].as<std::string>("");
  const YAML::Node config = node["config"];
  const std::string world = config["world"].as<std::string>("");
  if (scenario.empty() || world.empty()) {
    throw core::IoError(manifest.string() + ": names no scenario_file or config.world");
  }
  RunSetup setup;
  if (!config["sim"]["robot"]["radius"]) {
    throw core::IoError(manifest.string() + ": names no config.sim.robot.radius");
  }
  setup.robot_radius =
      io::ReadConfig<sim::RobotConfig>(config["sim"]["robot"], manifest.string()).radius;
  if (config["metrics"]) {
    setup.metrics = io::ReadConfig<MetricsConfig>(config["metrics"], manifest.string());
  }
  setup.world = sim::LoadWorld(scenario.parent_path() / world);
  return setup;
}

std::vector<RunTrace> ReadRuns(const std::filesystem::path& mode_dir) {
  std::vector<RunTrace> runs;
  for (int i = 0; std::filesystem::is_directory(mode_dir / "runs" / std::to_string(i)); ++i) {
    runs.push_back(ReadRunFolder(mode_dir / "runs" / std::to_string(i), i));
  }
  return runs;
}

// "run i", with the outcome of a run that did not succeed ("run 2 (timeout)"), from
// metrics.json when the folder has one.
std::vector<std::string> RunLabels(const std::filesystem::path& mode_dir,
                                   const std::vector<RunTrace>& runs) {
  std::vector<std::string> labels;
  nlohmann::json metrics;
  if (std::filesystem::is_regular_file(mode_dir / "metrics.json"))
    metrics = io::ReadJsonFile(mode_dir / "metrics.json");
  for (const RunTrace& run : runs) {
    std::string label = "run " + std::to_string(run.run);
    if (metrics.contains("runs")) {
      for (const nlohmann::json& r : metrics["runs"]) {
        if (r.value("run", -1) == run.run && r.value("outcome", "success") != "success") {
          label += " (" + r.value("outcome", std::string()) + ")";
        }
      }
    }
    labels.push_back(label);
  }
  return labels;
}

// The teaching drive's pose (truth, else odometry) at the trace's instant `time`.
core::Pose2 DrivePoseAt(const TeachTrace& trace, double time) {
  const std::vector<core::Pose2>& poses = trace.X_WR.empty() ? trace.X_OR : trace.X_WR;
  const auto it = std::lower_bound(trace.time.begin(), trace.time.end(), time);
  const std::size_t i = std::min<std::size_t>(it - trace.time.begin(), poses.size() - 1);
  return poses.at(i);
}

std::vector<viz::PartialMapView> MapViews(const ModeTeach& teach) {
  std::vector<viz::PartialMapView> views;
  for (std::size_t k = 0; k < teach.bundle.maps.size(); ++k) {
    const nav::PartialMap& map = teach.bundle.maps[k];
    const TeachMapTrace& ref = teach.trace.maps.at(k);
    viz::PartialMapView view;
    view.label = "map " + std::to_string(k);
    view.grid = map.grid;
    const core::Pose2 X_WR =
        ref.X_WR.empty() ? DrivePoseAt(teach.trace, ref.time.front()) : ref.X_WR.front();
    view.X_WM = X_WR * ref.X_MR.front().Inverse();
    view.path = map.path.poses();
    view.start = core::Pose2::Identity();
    if (k + 1 < teach.bundle.maps.size()) view.switch_pose = map.X_MS;
    views.push_back(std::move(view));
  }
  return views;
}

std::vector<core::Pose2> SwitchPosesW(const ModeTeach& teach) {
  std::vector<core::Pose2> out;
  for (std::size_t k = 0; k + 1 < teach.trace.maps.size(); ++k) {
    const TeachMapTrace& map = teach.trace.maps[k];
    out.push_back(map.X_WR.empty() ? DrivePoseAt(teach.trace, map.time.back()) : map.X_WR.back());
  }
  return out;
}

core::Pose2 PoseFrom(const nlohmann::json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

// The snapshot's scan points in M (from the true pose X_ML of the LiDAR), with their labels.
std::vector<viz::ScanPoint> ScanPointsOf(const nlohmann::json& scan, const core::Pose2& X_ML,
                                         bool simulated) {
  const double angle_min = scan.at("angle_min").get<double>(),
               increment = scan.at("angle_increment").get<double>();
  std::vector<viz::ScanPoint> points;
  for (std::size_t i = 0; i < scan.at("ranges").size(); ++i) {
    const nlohmann::json& r = scan.at("ranges")[i];
    if (!r.is_number()) continue;  // no return (written as null)
    const double range = r.get<double>(), a = angle_min + static_cast<double>(i) * increment;
    viz::ScanPoint point;
    point.point = X_ML * core::Vec2(range * std::cos(a), range * std::sin(a));
    point.rejected = scan.at("use")[i].get<int>() == 2;
    point.hits_pedestrian = simulated && scan.at("pedestrian")[i].get<int>() == 1;
    points.push_back(point);
  }
  return points;
}

// One of the snapshot's likelihood grids (log values, origin at the lower-left cell corner).
viz::LikelihoodGrid LikelihoodGridOf(const nlohmann::json& l, const char* key) {
  viz::LikelihoodGrid g;
  g.width = g.height = l.at("size").get<int>();
  g.resolution = l.at("resolution").get<double>();
  g.origin = core::Vec2(l.at("origin").at(0).get<double>() - 0.5 * g.resolution,
                        l.at("origin").at(1).get<double>() - 0.5 * g.resolution);
  for (const auto& v : l.at(key)) g.values.push_back(v.get<double>());
  g.log_values = true;
  return g;
}

}  // namespace

void RenderSnapshot(const std::filesystem::path& file, const ModeTeach& teach, double robot_radius,
                    const std::filesystem::path& figures,
                    std::vector<std::filesystem::path>* written) {
  const nlohmann::json j = io::ReadJsonFile(file);
  const int k = j.at("map").get<int>();
  const core::Pose2 X_WR = PoseFrom(j.at("X_WR"));
  const core::Pose2 truth = PoseFrom(j.at("X_MR_truth"));
  const core::Pose2 X_MW = truth * X_WR.Inverse();  // the local alignment at that moment
  const core::Pose2 X_RL = PoseFrom(j.at("X_RL"));
  std::vector<viz::Circle> pedestrians;
  for (const auto& p : j.at("pedestrians_W")) {
    pedestrians.push_back(
        {X_MW * core::Vec2(p.at(0).get<double>(), p.at(1).get<double>()), p.at(2).get<double>()});
  }

  viz::SnapshotData snap;
  snap.time_s = j.at("time_s").get<double>();
  snap.map_index = k;
  snap.grid = teach.bundle.maps.at(static_cast<std::size_t>(k)).grid;
  snap.path = teach.bundle.maps.at(static_cast<std::size_t>(k)).path.poses();
  for (const auto& p : j.at("particles")) {
    snap.particles.emplace_back(p.at(0).get<double>(), p.at(1).get<double>(),
                                p.at(2).get<double>());
    snap.weights.push_back(p.at(3).get<double>());
  }
  snap.estimate = PoseFrom(j.at("X_MR_estimate"));
  snap.truth = truth;
  const nlohmann::json& scan = j.at("scan");
  // A log's snapshot knows no pedestrians: its per-beam labels are empty.
  const bool simulated = !scan.at("pedestrian").empty();
  snap.simulated = simulated;
  snap.scan = ScanPointsOf(scan, truth * X_RL, simulated);
  snap.pedestrians = pedestrians;
  snap.robot_radius = robot_radius;
  written->push_back(viz::RenderSnapshotFigure(snap, figures / "snapshot.png").path);

  const nlohmann::json& l = j.at("likelihood");
  viz::LikelihoodFigureData like;
  like.without_rejection = LikelihoodGridOf(l, "all_beams");
  like.with_rejection = LikelihoodGridOf(l, "static_beams");
  like.true_pose = truth;
  like.pedestrians = pedestrians;
  like.time_s = snap.time_s;
  like.simulated = simulated;
  written->push_back(viz::RenderLikelihoodFigure(like, figures / "likelihood.png").path);
}

std::filesystem::path RenderTeachMaps(const ModeTeach& teach, const viz::WorldShapes& world,
                                      const std::filesystem::path& png, viz::RouteSource truth) {
  viz::MapsFigureData maps;
  maps.world = world;
  maps.route = teach.trace.X_WR.empty() ? teach.trace.X_OR : teach.trace.X_WR;
  maps.route_source = teach.trace.X_WR.empty() ? viz::RouteSource::kOdometry : truth;
  maps.switch_poses = SwitchPosesW(teach);
  maps.maps = MapViews(teach);
  return viz::RenderMapsFigure(maps, png).path;
}

namespace {

// Arc length of the teaching ground truth up to the end of each map but the last.
std::vector<double> SwitchArcLengths(const TeachTrace& trace) {
  std::vector<double> out;
  double s = 0.0;
  for (std::size_t k = 0; k + 1 < trace.maps.size(); ++k) {
    const core::Vec2 end = trace.maps[k].X_WR.back().translation();
    double best = 1e300, arc = 0.0;
    for (std::size_t i = 1; i < trace.X_WR.size(); ++i) {
      arc += (trace.X_WR[i].translation() - trace.X_WR[i - 1].translation()).norm();
      const double d = (trace.X_WR[i].translation() - end).norm();
      if (arc >= s && d < best) {
        best = d;
        s = arc;
      }
      if (best < 0.05) break;
    }
    out.push_back(s);
  }
  return out;
}

// A mode's figures of its playback runs: the drives, their errors, the odometry of the teaching
// drive and run 0, and run 0's snapshot.
void RenderRunFigures(const std::filesystem::path& dir, const std::string& mode_name,
                      const ModeTeach& teach, const RunSetup& setup,
                      const viz::WorldShapes& shapes, const std::vector<RunTrace>& runs,
                      std::vector<std::filesystem::path>* written) {
  const std::filesystem::path figures = dir / "figures";
  viz::PlaybackFigureData playback;
  playback.mode = mode_name;
  playback.world = shapes;
  playback.target = teach.trace.X_WR;
  playback.switch_poses = SwitchPosesW(teach);
  viz::ErrorsFigureData errors;
  errors.mode = mode_name;
  const std::vector<std::string> labels = RunLabels(dir, runs);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    std::vector<core::Pose2> poses;
    for (const PlaybackSample& s : runs[i].samples) poses.push_back(s.X_WR);
    playback.runs.push_back({labels[i], poses});
    const RunSeries series = ComputeRunSeries(teach.trace, runs[i], setup.metrics);
    errors.runs.push_back(
        {labels[i], series.progress_m, series.tracking_error_m, series.localization_error_m});
  }
  errors.switch_arc_lengths = SwitchArcLengths(teach.trace);
  written->push_back(
      viz::RenderPlaybackFigure(playback, figures / ("playback_" + mode_name + ".png")).path);
  written->push_back(viz::RenderErrorsFigure(errors, figures / "errors.png").path);

  viz::OdometryFigureData odometry;
  odometry.world = shapes;
  odometry.drives.push_back({"teaching", teach.trace.X_WR, teach.trace.X_OR});
  std::vector<core::Pose2> run_truth, run_odom;
  for (const PlaybackSample& p : runs.front().samples) {
    run_truth.push_back(p.X_WR);
    run_odom.push_back(p.X_OR);
  }
  odometry.drives.push_back({"playback run 0", run_truth, run_odom});
  written->push_back(viz::RenderOdometryFigure(odometry, figures / "odometry.png").path);

  if (std::filesystem::exists(dir / "runs/0/snapshot.json")) {
    RenderSnapshot(dir / "runs/0/snapshot.json", teach, setup.robot_radius, figures, written);
  }
}

// The comparison figure's numbers of one mode, from its metrics.json aggregate.
viz::ModeMetrics ModeMetricsOf(const std::string& mode_name, const nlohmann::json& a) {
  auto value = [](const nlohmann::json& v) {
    return v.is_number() ? v.get<double>() : std::nan("");
  };
  viz::ModeMetrics m;
  m.mode = mode_name;
  m.metrics.push_back({"success rate", value(a.at("success_rate"))});
  m.metrics.push_back(
      {"tracking RMS (m)", value(a.at("tracking_error_m").at("pooled").at("rms"))});
  m.metrics.push_back(
      {"localization RMS (m)", value(a.at("localization_error_m").at("pooled").at("rms"))});
  m.metrics.push_back({"repeatability (m)", value(a.at("repeatability_m"))});
  return m;
}

// The figures across modes: their metrics side by side, and the consistent map against the
// single odometry map.
void RenderAcrossModes(const std::filesystem::path& out, viz::ComparisonFigureData comparison,
                       const std::vector<std::pair<std::string, ModeTeach>>& teaches,
                       std::vector<std::filesystem::path>* written) {
  std::filesystem::create_directories(out / "figures");
  if (comparison.modes.size() > 1) {
    comparison.scenario = out.filename().string();
    comparison.note =
        "Each mode: the playback runs of one teaching drive; RMS over all the runs' samples "
        "(retrace compare gives confidence intervals over seeds).";
    written->push_back(
        viz::RenderComparisonFigure(comparison, out / "figures" / "comparison.png").path);
  }
  viz::MapsCompareFigureData compare;
  for (const char* name : {"consistent", "single"}) {
    for (const auto& [mode_name, teach] : teaches) {
      if (mode_name != name) continue;
      std::vector<viz::PartialMapView> views = MapViews(teach);
      views.front().label =
          std::string(name == std::string("single") ? "odometry map (single)" : "consistent map");
      compare.maps.push_back(views.front());
    }
  }
  if (compare.maps.size() == 2) {
    written->push_back(
        viz::RenderMapsCompareFigure(compare, out / "figures" / "maps_compare.png").path);
  }
}

}  // namespace

std::vector<std::filesystem::path> RenderResults(const std::filesystem::path& out) {
  std::vector<std::filesystem::path> written;
  std::vector<std::pair<std::string, ModeTeach>> teaches;
  viz::ComparisonFigureData comparison;
  for (const auto& [mode, name] : core::EnumTraits<MapMode>::kNames) {
    const std::string mode_name(name);
    const std::filesystem::path dir = out / mode_name;
    if (!std::filesystem::is_directory(dir / "teach")) continue;
    ModeTeach teach = ReadTeachFolder(dir / "teach", mode);
    const RunSetup setup = ReadRunSetup(dir);
    const viz::WorldShapes shapes = WorldShapesOf(setup.world.geometry);
    std::filesystem::create_directories(dir / "figures");
    written.push_back(RenderTeachMaps(teach, shapes, dir / "figures" / "maps.png"));
    const std::vector<RunTrace> runs = ReadRuns(dir);
    if (!runs.empty()) RenderRunFigures(dir, mode_name, teach, setup, shapes, runs, &written);
    if (std::filesystem::exists(dir / "metrics.json")) {
      comparison.modes.push_back(
          ModeMetricsOf(mode_name, io::ReadJsonFile(dir / "metrics.json").at("aggregate")));
    }
    teaches.emplace_back(mode_name, std::move(teach));
  }
  if (teaches.empty())
    throw core::IoError(out.string() +
                        ": holds no results of `retrace run` (no <mode>/teach folder)");
  RenderAcrossModes(out, std::move(comparison), teaches, &written);
  return written;
}

}  // namespace retrace::bench
