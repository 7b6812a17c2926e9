// retrace.log_teach, log_localize and log_simulate: the log commands as one library call each
// (bench/replay/log_teach_run.hpp, log_localize_run.hpp, bench/calibration/log_simulate_run.hpp).
// They report no progress; Ctrl-C stops them between reading the log and writing anything.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/calibration/log_simulate_run.hpp"
#include "bench/engine/mode_list.hpp"
#include "bench/replay/log_localize_run.hpp"
#include "bench/replay/log_teach_run.hpp"
#include "core/angle.hpp"
#include "io/json_writer.hpp"
#include "python/arguments.hpp"
#include "python/bindings.hpp"
#include "python/interruptible.hpp"
#include "python/json_to_python.hpp"
#include "python/log_arguments.hpp"

namespace retrace::python {
namespace py = pybind11;
using Path = std::filesystem::path;
using OptionalPath = std::optional<Path>;
namespace {

/// What retrace.log_teach, log_localize and log_simulate return.
struct LogResult {
  Path out;
  std::string summary;  ///< what the command line prints
  std::vector<std::string> notes;
  std::vector<std::string> modes;  ///< log_teach: the modes taught
  py::object metrics;              ///< log_localize: metrics.json
};

// A LogResult as the worker thread makes it: no Python objects without the GIL.
struct LogOutput {
  Path out;
  std::string summary;
  std::vector<std::string> notes, modes;
  std::optional<nlohmann::json> metrics;
};

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The log's computation, then, unless Ctrl-C came meanwhile, its output: write(computed, wall s)
// gives the LogOutput.
template <class Compute, class Write>
LogResult ComputeThenWrite(const Path& out, const Compute& compute, const Write& write) {
  PythonProgress progress(py::bool_(false));
  LogOutput output = CallInterruptibly(progress, CreatedFolders({out}), [&] {
    const auto start = std::chrono::steady_clock::now();
    const auto computed = compute();
    if (progress.Cancelled()) throw core::Interrupted();
    return write(computed, SecondsSince(start));
  });
  return {std::move(output.out), std::move(output.summary), std::move(output.notes),
          std::move(output.modes), output.metrics ? JsonToPython(*output.metrics) : py::none()};
}

// --switch-points auto|online|s1,s2,... as the key route.switch_points.
std::string SwitchPointsOverride(const std::string& text) {
  if (text == "auto" || text == "online") return "route.switch_points=" + text;
  return "route.switch_points=[" + text + "]";
}

LogResult LogTeach(const LogArguments& a, const py::object& modes,
                   const std::optional<std::string>& switch_points) {
  bench::LogTeachRequest request;
  request.run = LogRunOptionsOf(a);
  if (switch_points) request.extra_overrides.push_back(SwitchPointsOverride(*switch_points));
  const std::vector<std::string> names = NameList(modes, "modes");
  if (!names.empty()) request.modes = bench::ParseModeList(names, "modes");
  CallText call = LogCallText("log_teach", a);
  call.Keyword("modes", modes);
  if (switch_points) call.Keyword("switch_points", py::str(*switch_points));
  const std::string command = call.str();
  return ComputeThenWrite(
      request.run.out, [&] { return bench::TeachLog(request); },
      [&](const bench::LogTeaching& taught, double wall_s) {
        LogOutput result{taught.request.run.out, "", {}, {}, std::nullopt};
        result.notes = bench::WriteLogTeachFolder(taught, command, wall_s);
        result.summary = bench::LogTeachSummary(taught, result.notes);
        for (const bench::ModeTeach& mode : taught.result.modes)
          result.modes.emplace_back(core::EnumName(mode.mode));
        return result;
      });
}

std::optional<core::Pose2> InitialPose(const std::optional<std::vector<double>>& pose) {
  if (!pose) return std::nullopt;
  if (pose->size() != 3) {
    throw core::ConfigError("initial_pose",
                            "must be (x, y, yaw_deg): m, m and degrees in map 0, "
                            "got " +
                                std::to_string(pose->size()) + " numbers");
  }
  return core::Pose2((*pose)[0], (*pose)[1], core::DegToRad((*pose)[2]));
}

LogResult LogLocalize(const LogArguments& a, const Path& teach,
                      const std::optional<std::vector<double>>& initial_pose,
                      bool every_odometry_tick) {
  bench::LogLocalizeRequest request;
  request.run = LogRunOptionsOf(a);
  request.teach_dir = teach;
  request.initial = InitialPose(initial_pose);
  request.every_odometry_tick = every_odometry_tick;
  const std::string command = LogCallText("log_localize", a).Keyword("teach", teach).str();
  return ComputeThenWrite(
      request.run.out, [&] { return bench::LocalizeLog(request); },
      [&](const bench::LogLocalization& localized, double wall_s) {
        std::vector<std::string> notes = bench::WriteLogLocalizeFolder(localized, command, wall_s);
        const Path& out = localized.request.run.out;
        return LogOutput{out,
                         bench::LogLocalizeSummary(localized),
                         std::move(notes),
                         {},
                         io::ReadJsonFile(out / "metrics.json")};
      });
}

LogResult LogSimulate(const LogArguments& a, const Path& teach) {
  bench::LogSimulateRequest request{LogRunOptionsOf(a), teach};
  // SimulateLogFile writes the file itself (staged); Ctrl-C waits for it.
  return ComputeThenWrite(
      request.run.out, [&] { return bench::SimulateLogFile(request); },
      [&](const bench::SimulatedLog& simulated, double) {
        return LogOutput{
            request.run.out, bench::LogSimulateSummary(simulated), {}, {}, std::nullopt};
      });
}

void BindLogResult(py::module_& m) {
  py::class_<LogResult>(m, "LogResult", "A log command done and its output written.")
      .def_readonly("out", &LogResult::out, "the folder (log_simulate: the MCAP file) written")
      .def_readonly("summary", &LogResult::summary, "what the command line prints")
      .def_readonly("notes", &LogResult::notes, "notes about the log and what was not written")
      .def_readonly("modes", &LogResult::modes, "log_teach: the modes taught")
      .def_readonly("metrics", &LogResult::metrics, "log_localize: metrics.json (else None)")
      .def("__repr__",
           [](const LogResult& r) { return "LogResult(out='" + r.out.string() + "')"; });
}

// The arguments every log function shares, as one struct.
LogArguments Arguments(const Path& log, const OptionalPath& out, bool figures,
                       std::optional<double> from_s, std::optional<double> to_s,
                       bool synthetic_odometry, const OptionalPath& reference,
                       const OptionalPath& config, py::object set, py::object seed,
                       std::string scan, std::string odometry, std::string reference_topic,
                       std::string odom_frame, std::string base_frame) {
  StreamArguments streams{std::move(scan), std::move(odometry), std::move(reference_topic),
                          std::move(odom_frame), std::move(base_frame)};
  return {log,    out, from_s, to_s,    synthetic_odometry, reference,
          config, set, seed,   figures, std::move(streams)};
}

// Defines `name` with `own` (the log and the function's own keywords) followed by the keywords
// every log function shares, which `f` takes last: from_s, to_s, synthetic_odometry, reference,
// config, set, seed and the five stream choices (StreamArguments).
template <typename F, typename... Own>
void DefLogFunction(py::module_& m, const char* name, F&& f, const char* doc, Own&&... own) {
  m.def(name, std::forward<F>(f), std::forward<Own>(own)..., py::arg("from_s") = py::none(),
        py::arg("to_s") = py::none(), py::arg("synthetic_odometry") = false,
        py::arg("reference") = py::none(), py::arg("config") = py::none(),
        py::arg("set") = py::none(), py::arg("seed") = py::none(), py::arg("scan_topic") = "",
        py::arg("odometry_topic") = "", py::arg("reference_topic") = "",
        py::arg("odom_frame") = "odom", py::arg("base_frame") = "", doc);
}

void BindLogTeach(py::module_& m) {
  DefLogFunction(
      m, "log_teach",
      [](const Path& log, const OptionalPath& out, py::object modes,
         const std::optional<std::string>& switch_points, bool figures,
         std::optional<double> from_s, std::optional<double> to_s, bool synthetic_odometry,
         const OptionalPath& reference, const OptionalPath& config, py::object set, py::object seed,
         std::string scan, std::string odometry, std::string reference_topic,
         std::string odom_frame, std::string base_frame) {
        return LogTeach(
            Arguments(log, out, figures, from_s, to_s, synthetic_odometry, reference, config, set,
                      seed, scan, odometry, reference_topic, odom_frame, base_frame),
            modes, switch_points);
      },
      "`retrace log-teach`: the teach folders (<out>/<mode>/teach) of a recorded log's drive. "
      "switch_points: 'online' (default), 'auto' or 's1,s2,...' (m along the driven path). "
      "Returns a LogResult.",
      py::arg("log"), py::kw_only(), py::arg("out"), py::arg("modes") = py::none(),
      py::arg("switch_points") = py::none(), py::arg("figures") = true);
}

void BindLogLocalize(py::module_& m) {
  DefLogFunction(
      m, "log_localize",
      [](const Path& log, const Path& teach, const OptionalPath& out,
         const std::optional<std::vector<double>>& initial_pose, bool every_odometry_tick,
         bool figures, std::optional<double> from_s, std::optional<double> to_s,
         bool synthetic_odometry, const OptionalPath& reference, const OptionalPath& config,
         py::object set, py::object seed, std::string scan, std::string odometry,
         std::string reference_topic, std::string odom_frame, std::string base_frame) {
        return LogLocalize(
            Arguments(log, out, figures, from_s, to_s, synthetic_odometry, reference, config, set,
                      seed, scan, odometry, reference_topic, odom_frame, base_frame),
            teach, initial_pose, every_odometry_tick);
      },
      "`retrace log-localize`: localize a recorded log in the maps of the teach folder `teach`, "
      "against its reference, and write the results folder `out`. initial_pose: (x, y, yaw_deg) "
      "in map 0. Returns a LogResult with metrics.",
      py::arg("log"), py::kw_only(), py::arg("teach"), py::arg("out"),
      py::arg("initial_pose") = py::none(), py::arg("every_odometry_tick") = false,
      py::arg("figures") = true);
}

void BindLogSimulate(py::module_& m) {
  DefLogFunction(
      m, "log_simulate",
      [](const Path& log, const Path& teach, const Path& out, std::optional<double> from_s,
         std::optional<double> to_s, bool synthetic_odometry, const OptionalPath& reference,
         const OptionalPath& config, py::object set, py::object seed, std::string scan,
         std::string odometry, std::string reference_topic, std::string odom_frame,
         std::string base_frame) {
        return LogSimulate(
            Arguments(log, out, false, from_s, to_s, synthetic_odometry, reference, config, set,
                      seed, scan, odometry, reference_topic, odom_frame, base_frame),
            teach);
      },
      "`retrace log-simulate`: drive the log's reference again in the simulator, in the "
      "consistent map of `teach`, and write the simulated log `out` (MCAP). Returns a "
      "LogResult.",
      py::arg("log"), py::kw_only(), py::arg("teach"), py::arg("out"));
}

}  // namespace

void BindLogs(py::module_& m) {
  BindLogResult(m);
  BindLogTeach(m);
  BindLogLocalize(m);
  BindLogSimulate(m);
}

}  // namespace retrace::python
