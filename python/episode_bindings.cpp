// retrace.Teaching and retrace.Episode: playback runs stepped from Python (docs/PYTHON.md, "Your
// own stack in the loop"; bench/run/stepped_episode.hpp). The teaching drive's recording, each
// step's sensor data and the taught maps come out as NumPy arrays that view retrace's memory
// where it lives as long as the Python object holding it.

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/engine/mode_list.hpp"
#include "bench/metrics/metrics_json.hpp"
#include "bench/run/stepped_episode.hpp"
#include "core/errors.hpp"
#include "core/occupancy_grid.hpp"
#include "io/ros_map.hpp"
#include "python/arguments.hpp"
#include "python/bindings.hpp"
#include "python/interruptible.hpp"
#include "python/json_to_python.hpp"
#include "python/numpy_arrays.hpp"
#include "python/pose_arrays.hpp"
#include "python/scan_objects.hpp"
#include "python/stack_answer.hpp"
#include "python/taught_maps.hpp"

namespace retrace::python {
namespace py = pybind11;
namespace {

using bench::OdometryIncrement;
using bench::OdometryReading;

// (N, 3) [t, distance, dtheta] of odometry increments.
py::array_t<double> IncrementArray(const std::vector<OdometryIncrement>& increments) {
  std::vector<double> values;
  values.reserve(increments.size() * 3);
  for (const OdometryIncrement& i : increments) {
    values.insert(values.end(), {i.time, i.delta.distance, i.delta.dtheta});
  }
  return OwningArray(std::move(values), {static_cast<py::ssize_t>(increments.size()), 3});
}

// (N, 4) [t, x, y, yaw] of odometry readings.
py::array_t<double> OdometryArray(const std::vector<OdometryReading>& readings) {
  std::vector<double> values;
  values.reserve(readings.size() * 4);
  for (const OdometryReading& r : readings) {
    values.insert(values.end(), {r.time, r.X_OR.x, r.X_OR.y, r.X_OR.theta});
  }
  return OwningArray(std::move(values), {static_cast<py::ssize_t>(readings.size()), 4});
}

py::array_t<double> PoseRows(const std::vector<core::Pose2>& poses) {
  std::vector<double> values;
  values.reserve(poses.size() * 3);
  for (const core::Pose2& p : poses) values.insert(values.end(), {p.x, p.y, p.theta});
  return OwningArray(std::move(values), {static_cast<py::ssize_t>(poses.size()), 3});
}

py::array_t<double> PoseVector(const core::Pose2& p) {
  return OwningArray(std::vector<double>{p.x, p.y, p.theta}, {3});
}

/// The teaching drive as recorded: what a stack that builds its own maps is given.
struct Recording {
  py::list scans;
  py::array_t<double> odometry;
  py::array_t<double> reference;
};

/// One map retrace taught, in its own frame.
struct TaughtMap {
  int index = 0;
  py::array_t<std::uint8_t> image;
  py::object log_odds;  ///< (H, W) float64, or None: a map read from a teach folder's image
  double resolution = 0.0;
  py::tuple origin;
  py::array_t<double> path;
  py::array_t<double> switch_pose;
};

// A cell as map_saver's trinary image classifies it with its default thresholds (the teach
// folders' maps/ogm_<k>: io::RosMapWriteOptions): 0 occupied, 254 free, 205 unknown.
std::uint8_t TrinaryPixel(float log_odds) {
  const io::RosMapWriteOptions thresholds;
  const double p = core::InverseLogit(log_odds);
  if (p > thresholds.occupied_thresh) return 0;
  return p < thresholds.free_thresh ? 254 : 205;
}

// A TaughtMap built in Python (the results reader), its arrays' shapes checked.
TaughtMap MakeTaughtMap(int index, const py::array_t<std::uint8_t>& image, double resolution,
                        const std::pair<double, double>& origin, const py::array_t<double>& path,
                        const py::array_t<double>& switch_pose, const py::object& log_odds) {
  if (image.ndim() != 2) throw py::value_error("image: an (H, W) uint8 array");
  if (!(resolution > 0.0)) throw py::value_error("resolution: m per cell, > 0");
  if (path.ndim() != 2 || path.shape(1) != 3) throw py::value_error("path: an (N, 3) array");
  if (switch_pose.ndim() != 1 || switch_pose.shape(0) != 3) {
    throw py::value_error("switch_pose: (x, y, yaw)");
  }
  if (!log_odds.is_none()) {
    const auto l = log_odds.cast<py::array_t<double>>();
    if (l.ndim() != 2 || l.shape(0) != image.shape(0) || l.shape(1) != image.shape(1)) {
      throw py::value_error("log_odds: None or an array of the image's shape");
    }
  }
  return {index, image,      log_odds, resolution, py::make_tuple(origin.first, origin.second),
          path,  switch_pose};
}

TaughtMap ToTaughtMap(int index, const nav::PartialMap& map) {
  const core::OccupancyGrid& grid = map.grid;
  std::vector<std::uint8_t> pixels;
  std::vector<double> log_odds;
  pixels.reserve(grid.log_odds().size());
  log_odds.reserve(grid.log_odds().size());
  for (const float l : grid.log_odds()) {
    pixels.push_back(TrinaryPixel(l));
    log_odds.push_back(l);
  }
  const std::vector<py::ssize_t> shape{grid.height(), grid.width()};
  return {index,
          OwningArray(std::move(pixels), shape),
          OwningArray(std::move(log_odds), shape),
          grid.resolution(),
          py::make_tuple(grid.origin().x(), grid.origin().y()),
          PathArray(map.path),
          PoseVector(map.X_MS)};
}

/// retrace.Teaching: a scenario taught once, in one map mode.
class Teaching {
 public:
  explicit Teaching(std::shared_ptr<const bench::SteppedTeaching> taught)
      : taught_(std::move(taught)) {}

  const bench::SteppedTeaching& taught() const { return *taught_; }
  std::shared_ptr<const bench::SteppedTeaching> shared() const { return taught_; }

  const py::list& maps() {
    if (!maps_) {
      maps_.emplace(TaughtMapList(taught_->teach.bundle));
    }
    return *maps_;
  }
  const Recording& recording() {
    if (!recording_) {
      const bench::TeachRecording& r = taught_->recording;
      recording_ = Recording{ScanList(r.scans), OdometryArray(r.odometry), PoseRows(r.X_WR)};
    }
    return *recording_;
  }

 private:
  std::shared_ptr<const bench::SteppedTeaching> taught_;
  std::optional<py::list> maps_;
  std::optional<Recording> recording_;
};

/// What one step's observe() returns.
struct Observation {
  double time = 0.0;
  py::array_t<double> odometry;
  py::list scans;
  bool handed_back = false;
};

/// retrace.Episode: one playback run of a Teaching.
class Episode {
 public:
  Episode(const Teaching& teaching, int run, bool builtin)
      : episode_(std::make_unique<bench::SteppedEpisode>(teaching.shared(), run, builtin)),
        builtin_(builtin) {}

  bench::SteppedEpisode& stepped() { return *episode_; }
  bool builtin() const { return builtin_; }

  // A step out of order is a RuntimeError (core::Error), with what to do instead.
  Observation Observe() {
    if (episode_->done()) {
      throw core::Error("observe: the run is done (episode.done); metrics() has its results");
    }
    if (observed_) {
      throw core::Error(
          "observe: the last observation is not answered yet: act(v, omega, estimate=(x, y, yaw), "
          "map=k) first");
    }
    const bench::Observation& o = episode_->Observe();
    observed_ = true;
    return {o.time, IncrementArray(o.odometry), ScanList(o.scans), o.handed_back};
  }

  // The keywords of act() beside the command and the estimate: a registered stack's answer's
  // (python/stack_answer.hpp).
  struct ActKeywords {
    int map = 0;
    bool lost = false, off_map = false, route_done = false;
    bool modified = false, blocked = false, emergency_stop = false;
    py::object map_change;
  };

  bool Act(const py::object& v, const py::object& omega, const py::object& estimate,
           const ActKeywords& k) {
    if (!observed_) throw core::Error("act: nothing to answer yet: observe() first");
    if (builtin_) {
      if (!estimate.is_none() || !v.is_none() || !omega.is_none()) {
        throw core::ConfigError("answer", "the built-in stack answers this episode: act()");
      }
      const bool done = episode_->Act(std::nullopt);
      observed_ = false;
      return done;
    }
    if (v.is_none() || omega.is_none()) {
      throw core::ConfigError("command",
                              "missing: act(v, omega, estimate=(x, y, yaw), map=k) needs the "
                              "command, v in m/s and omega in rad/s");
    }
    if (k.map < 0) throw core::ConfigError("map", "must be >= 0");
    // Built directly, not through a dict: this runs at every control tick.
    bench::StackOutput answer;
    answer.drive = {
        {Number(v, "v"), Number(omega, "omega")}, k.modified, k.blocked, k.emergency_stop};
    answer.X_MR = EstimateArgument(estimate);
    answer.map = static_cast<std::size_t>(k.map);
    answer.lost = k.lost;
    answer.off_map = k.off_map;
    answer.route_done = k.route_done;
    if (!k.map_change.is_none()) answer.map_change = MapChangeOf(k.map_change, "act()");
    const bool done = episode_->Act(answer);  // checks the maps (SteppedEpisode::Act)
    observed_ = false;
    return done;
  }

  py::object Metrics() {
    if (!episode_->done()) {
      throw core::Error("metrics: the run is not done yet: observe() and act() until done");
    }
    return JsonToPython(bench::ToJson(episode_->Metrics()));
  }

  // The last control tick as the harness saw it (None before the first act()).
  py::object Tick() {
    const bench::PlaybackSample* s = episode_->LastSample();
    if (s == nullptr) return py::none();
    py::dict d;
    d["time"] = s->time;
    d["map"] = s->map_index;
    d["gt"] = PoseVector(s->X_WR);
    d["clearance"] = s->clearance;
    d["pedestrian_gap"] = s->pedestrian_gap;
    d["collisions"] = episode_->Collisions();
    return d;
  }

  py::dict Samples() {
    const bench::RunTrace& trace = episode_->trace();
    std::vector<double> time;
    std::vector<double> map;
    std::vector<core::Pose2> est;
    std::vector<core::Pose2> truth;
    std::vector<core::Pose2> odom;
    std::vector<double> command;
    for (const bench::PlaybackSample& s : trace.samples) {
      time.push_back(s.time);
      map.push_back(s.map_index);
      est.push_back(s.X_MR);
      truth.push_back(s.X_WR);
      odom.push_back(s.X_OR);
      command.insert(command.end(), {s.command.v, s.command.omega});
    }
    const auto n = static_cast<py::ssize_t>(time.size());
    py::dict d;
    d["time"] = OwningArray(std::move(time), {n});
    d["map"] = OwningArray(std::move(map), {n});
    d["est"] = PoseRows(est);
    d["gt"] = PoseRows(truth);
    d["odom"] = PoseRows(odom);
    d["command"] = OwningArray(std::move(command), {n, 2});
    return d;
  }

 private:
  // (x, y, yaw): a sequence of three finite numbers.
  static double Number(const py::object& value, const char* name) {
    try {
      return value.cast<double>();
    } catch (const py::cast_error&) {
      throw py::type_error(std::string(name) + ": a number");
    }
  }

  static core::Pose2 EstimateArgument(const py::object& estimate) {
    if (estimate.is_none()) {
      throw core::ConfigError(
          "estimate",
          "missing: act() needs the stack's estimate (x, y, yaw) in map `map`'s frame, which the "
          "run is scored on (a stack that does not localize passes its dead-reckoned pose)");
    }
    std::vector<double> values;
    try {
      values = estimate.cast<std::vector<double>>();
    } catch (const py::cast_error&) {
      throw py::type_error("estimate: (x, y, yaw), a sequence of three numbers");
    }
    if (values.size() != 3) {
      throw core::ConfigError(
          "estimate", "must be (x, y, yaw), not " + std::to_string(values.size()) + " numbers");
    }
    return {values[0], values[1], values[2]};
  }

  std::unique_ptr<bench::SteppedEpisode> episode_;
  bool builtin_;
  bool observed_ = false;  // an observation waits for its answer
};

std::string TeachingRepr(const Teaching& t) {
  const bench::SteppedTeaching& s = t.taught();
  return "Teaching('" + s.scenario.config.name + "', mode='" +
         std::string(core::EnumName(s.teach.mode)) + "', " +
         std::to_string(s.teach.bundle.maps.size()) + " maps)";
}

void BindTeachingTypes(py::module_& m) {
  py::class_<Recording>(m, "Recording",
                        "The teaching drive as its sensors saw it, to build maps of one's own.")
      .def_readonly("scans", &Recording::scans, "[Scan], in time order")
      .def_readonly("odometry", &Recording::odometry,
                    "(N, 4) [t, x, y, yaw]: each wheel odometry reading X_OR, in the drive's "
                    "odometry frame O")
      .def_readonly("reference", &Recording::reference,
                    "(N, 3) [x, y, yaw]: the ground truth X_WR at each odometry reading");
  py::class_<TaughtMap>(m, "TaughtMap",
                        "One map retrace taught, in its own frame M: Teaching.maps, a Python "
                        "stack's context['maps'] and load_results(...).modes[m].teach.maps.")
      .def(py::init(&MakeTaughtMap), py::kw_only(), py::arg("index"), py::arg("image"),
           py::arg("resolution"), py::arg("origin"), py::arg("path"), py::arg("switch_pose"),
           py::arg("log_odds") = py::none())
      .def_readonly("index", &TaughtMap::index, "k: the map's place on the route")
      .def_readonly("image", &TaughtMap::image,
                    "(H, W) uint8: 0 occupied, 254 free, 205 unknown, row 0 the lowest y (as "
                    "read_map)")
      .def_readonly("log_odds", &TaughtMap::log_odds,
                    "(H, W) float64: each cell's log-odds (None for a map read from a teach "
                    "folder, whose image keeps only the three classes)")
      .def_readonly("resolution", &TaughtMap::resolution, "m per cell")
      .def_readonly("origin", &TaughtMap::origin, "(x, y) of the lower-left corner, m")
      .def_property_readonly(
          "extent",
          [](const TaughtMap& t) {
            const auto x = t.origin[0].cast<double>();
            const auto y = t.origin[1].cast<double>();
            return py::make_tuple(x, x + static_cast<double>(t.image.shape(1)) * t.resolution, y,
                                  y + static_cast<double>(t.image.shape(0)) * t.resolution);
          },
          "(left, right, bottom, top) in m, for matplotlib's imshow")
      .def_readonly("path", &TaughtMap::path, "(N, 3) [x, y, yaw]: the taught path in M")
      .def_readonly("switch_pose", &TaughtMap::switch_pose,
                    "(3,) X_MS: where the next map starts, in M (eq. 1: X_{M'R} = X_MS^-1 X_MR)");
}

void BindEpisodeTypes(py::module_& m) {
  py::class_<Observation>(m, "Observation", "What the sensors gave since the last step.")
      .def_readonly("time", &Observation::time, "s since the run started: the control tick's")
      .def_readonly("odometry", &Observation::odometry,
                    "(K, 3) [t, distance, dtheta]: each odometry increment since the last step, "
                    "as every stack is given odometry (integrate_odometry adds one to a pose)")
      .def_readonly("scans", &Observation::scans, "[Scan] since the last step (often one or none)")
      .def_readonly("handed_back", &Observation::handed_back,
                    "an operator drove the robot (a scripted takeover: the answers were ignored "
                    "meanwhile) and handed it back at the last tick: find the place again");
  py::class_<Episode>(m, "Episode", "One playback run, stepped: observe(), act(), until done.")
      .def_property_readonly(
          "run", [](Episode& e) { return e.stepped().run(); }, "the run's index (its seed)")
      .def_property_readonly(
          "maps", [](Episode& e) { return e.stepped().maps(); }, "the route's number of maps")
      .def_property_readonly(
          "done", [](Episode& e) { return e.stepped().done(); }, "the run has ended")
      .def("observe", &Episode::Observe,
           "Steps the world to the next control tick (1 / nav.control_rate_hz s); returns the "
           "Observation on the way. Raises RuntimeError when the run is done or the last "
           "observation was not answered.")
      .def(
          "act",
          [](Episode& e, const py::object& v, const py::object& omega, const py::object& estimate,
             int map, bool lost, bool off_map, bool route_done, bool modified, bool blocked,
             bool emergency_stop, const py::object& map_change) {
            return e.Act(
                v, omega, estimate,
                {map, lost, off_map, route_done, modified, blocked, emergency_stop, map_change});
          },
          py::arg("v") = py::none(), py::arg("omega") = py::none(), py::kw_only(),
          py::arg("estimate") = py::none(), py::arg("map") = 0, py::arg("lost") = false,
          py::arg("off_map") = false, py::arg("route_done") = false, py::arg("modified") = false,
          py::arg("blocked") = false, py::arg("emergency_stop") = false,
          py::arg("map_change") = py::none(),
          "Answers the last observation as a stack answers (docs/PYTHON.md): the command (v "
          "m/s, omega rad/s), the estimate (x, y, yaw) in map `map`'s frame (scored against the "
          "truth there), and the keywords map, lost, off_map, route_done (on the last map: the "
          "run ends, a success when the robot is within limits.lost_distance of the end), "
          "modified, blocked, emergency_stop and map_change ((from, to, X_MkR, X_MnR); without "
          "it a change of map is one from the last estimate). A built-in episode takes act() "
          "with no arguments. Returns done.")
      .def("metrics", &Episode::Metrics,
           "The run's metrics once done, as an entry of <mode>/metrics.json's runs.")
      .def_property_readonly(
          "tick", &Episode::Tick,
          "The last control tick as the harness recorded it, for a learning agent's reward "
          "(ground truth: never for a stack's estimate): {'time', 'map', 'gt' (3,) X_WR, "
          "'clearance' (m to the nearest static surface), 'pedestrian_gap' (m to the nearest "
          "person, inf: none), 'collisions' (so far)}; None before the first act().")
      .def("samples", &Episode::Samples,
           "The run's control ticks once done: {'time' (N,), 'map' (N,), 'est', 'gt', 'odom' "
           "(N, 3) [x, y, yaw], 'command' (N, 2) [v, omega]}.")
      .def("__repr__", [](Episode& e) {
        return "Episode(run=" + std::to_string(e.stepped().run()) +
               (e.builtin() ? ", builtin" : "") + (e.stepped().done() ? ", done)" : ")");
      });
}

py::object Aggregate(const Teaching& t, const std::vector<Episode*>& episodes) {
  std::vector<const bench::RunTrace*> runs;
  for (Episode* e : episodes) {
    if (&e->stepped().teaching() != &t.taught()) {
      throw core::ConfigError("episodes", "an episode of another Teaching");
    }
    runs.push_back(&e->stepped().trace());
  }
  return JsonToPython(bench::ToJson(bench::AggregateSteppedRuns(t.taught(), runs)));
}

void BindTeaching(py::module_& m) {
  py::class_<Teaching>(m, "Teaching",
                       "A scenario's route taught once in one map mode, for stepped runs.")
      .def(py::init([](const std::filesystem::path& scenario, const std::string& mode,
                       const py::object& seed, const py::object& set, const py::object& progress) {
             bench::TeachingRequest request;
             request.scenario = scenario;
             request.mode = mode;
             request.seed = Seed(seed);
             request.overrides = Overrides(set);
             PythonProgress sink(progress);
             return Teaching(CallInterruptibly(sink, CreatedFolders({}), [&] {
               return bench::TeachForStepping(request, &sink);
             }));
           }),
           py::arg("scenario"), py::kw_only(), py::arg("mode") = "partial",
           py::arg("seed") = py::none(), py::arg("set") = py::none(),
           py::arg("progress") = py::none(),
           "Loads the scenario and drives its route once, recording it and teaching the maps of "
           "`mode` (one of partial, scan_matched, single, consistent). set: overrides as for "
           "retrace.run.")
      .def_property_readonly(
          "mode", [](const Teaching& t) { return core::EnumName(t.taught().teach.mode); },
          "the map mode")
      .def_property_readonly(
          "seed", [](const Teaching& t) { return t.taught().scenario.config.seed; },
          "the scenario's seed")
      .def_property_readonly("maps", &Teaching::maps, "[TaughtMap], in route order")
      .def_property_readonly("recording", &Teaching::recording, "the teaching drive: Recording")
      .def_property_readonly(
          "lidar_mount",
          [](const Teaching& t) { return PoseVector(t.taught().scenario.robot.X_RL); },
          "(3,) X_RL: the LiDAR frame in the robot frame (scans are in L)")
      .def_property_readonly(
          "robot_radius", [](const Teaching& t) { return t.taught().scenario.robot.radius; }, "m")
      .def_property_readonly(
          "control_rate_hz",
          [](const Teaching& t) { return t.taught().scenario.config.nav.control_rate_hz; },
          "steps per simulated second")
      .def(
          "episode",
          [](const Teaching& t, int run, bool builtin) { return Episode(t, run, builtin); },
          py::arg("run") = 0, py::kw_only(), py::arg("builtin") = false,
          "Playback run `run` (its seed as `retrace run`'s run of that index). builtin: "
          "retrace's own stack (playback.stack) answers and act() takes no arguments.")
      .def("aggregate", &Aggregate, py::arg("episodes"),
           "The metrics over these finished episodes, as <mode>/metrics.json's aggregate "
           "(success rate, repeatability across them, the taught maps' quality).")
      .def("__repr__", &TeachingRepr);
}

}  // namespace

py::list TaughtMapList(const nav::TeachBundle& bundle) {
  py::list maps;
  for (std::size_t k = 0; k < bundle.maps.size(); ++k) {
    maps.append(ToTaughtMap(static_cast<int>(k), bundle.maps[k]));
  }
  return maps;
}

void BindEpisodes(py::module_& m) {
  m.def(
      "integrate_odometry",
      [](const py::object& pose, double distance, double dtheta) {
        const std::vector<double> p = pose.cast<std::vector<double>>();
        if (p.size() != 3) throw py::value_error("pose: (x, y, yaw)");
        const core::Pose2 X = core::IntegrateOdometry({p[0], p[1], p[2]}, {distance, dtheta});
        return py::make_tuple(X.x, X.y, X.theta);
      },
      py::arg("pose"), py::arg("distance"), py::arg("dtheta"),
      "The pose (x, y, yaw) moved by one odometry increment, along the arc at the midpoint "
      "heading: exactly as retrace's stacks and its simulated odometry integrate it.");
  BindScan(m);
  BindTeachingTypes(m);
  BindEpisodeTypes(m);
  BindTeaching(m);
}

}  // namespace retrace::python
