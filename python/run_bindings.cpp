// retrace.run, retrace.teach and retrace.playback: `retrace run`, `teach` and `playback` as one
// library call each (bench/run/scenario_run.hpp), interruptible, and their RunResult.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include "bench/engine/mode_list.hpp"
#include "bench/metrics/metrics_json.hpp"
#include "bench/output/html_report.hpp"
#include "bench/output/results_io.hpp"
#include "bench/run/scenario_run.hpp"
#include "python/arguments.hpp"
#include "python/bindings.hpp"
#include "python/call_text.hpp"
#include "python/interruptible.hpp"
#include "python/json_to_python.hpp"

namespace retrace::python {
namespace py = pybind11;
using Path = std::filesystem::path;
namespace {

/// One mode of a run: its runs and successes and, when runs were played back, the aggregate
/// metrics (the "aggregate" of <mode>/metrics.json).
struct ModeResult {
  std::string mode;
  int runs = 0;
  int successes = 0;
  py::object metrics;
};

/// What retrace.run, teach and playback return.
struct RunResult {
  Path out;
  int exit_code = 0;
  std::string summary;
  py::dict modes;
};

// The arguments the three calls share, as Python gave them (checked by ScenarioRequest).
struct RunArguments {
  Path scenario;
  py::object modes, seed, repeats, set, jobs;
  std::optional<Path> out, record_log, teach;
  bool figures = true, video = false;
  int video_run = 0;
  double video_speed = 10.0;
};

bench::ScenarioRunRequest ScenarioRequest(const RunArguments& a, bench::RunPhases phases) {
  bench::ScenarioRunRequest request;
  request.scenario = a.scenario;
  request.phases = phases;
  request.modes = NameList(a.modes, a.teach ? "mode" : "modes");
  // Checked here to name the argument as Python spells it (the library names --mode).
  if (!request.modes.empty()) bench::ParseModeList(request.modes, a.teach ? "mode" : "modes");
  request.seed = Seed(a.seed);
  request.repeats = BoundedInt(a.repeats, "repeats", 1);
  request.overrides = Overrides(a.set);
  request.jobs = BoundedInt(a.jobs, "jobs", 0).value_or(0);
  request.out = a.out.value_or(Path());
  request.record_log = a.record_log.value_or(Path());
  request.teach_dir = a.teach.value_or(Path());
  request.figures = a.figures;
  request.video = a.video;
  request.video_run = *BoundedInt(py::int_(a.video_run), "video_run", 0);
  request.video_speedup = PositiveNumber(a.video_speed, "video_speed");
  return request;
}

std::string RunCallText(const char* function, const RunArguments& a) {
  CallText call(function);
  call.Positional(a.scenario).Keyword("teach", a.teach.value_or(Path()));
  call.Keyword(a.teach ? "mode" : "modes", a.modes).Keyword("seed", a.seed);
  call.Keyword("repeats", a.repeats).Keyword("set", a.set).Keyword("jobs", a.jobs);
  call.Keyword("out", a.out.value_or(Path())).Keyword("record_log", a.record_log.value_or(Path()));
  if (!a.figures) call.Keyword("figures", py::bool_(false));
  if (a.video) call.Keyword("video", py::bool_(true)).Keyword("video_run", py::int_(a.video_run));
  return call.str();
}

RunResult ToRunResult(const bench::ScenarioRun& run) {
  RunResult result{run.out, run.exit_code, run.summary, {}};
  for (const bench::ModeSummary& mode : run.modes) {
    const std::string name(core::EnumName(mode.mode));
    py::object metrics = mode.runs > 0 ? JsonToPython(bench::ToJson(mode.aggregate)) : py::none();
    result.modes[py::str(name)] = ModeResult{name, mode.runs, mode.successes, metrics};
  }
  return result;
}

// The call: the run, then (unless teach only) report.html, a failure of which is a warning.
RunResult Run(const RunArguments& a, bench::RunPhases phases, bool report,
              const py::object& progress_arg, const char* function) {
  const bench::ScenarioRunRequest request = ScenarioRequest(a, phases);
  const std::string command = RunCallText(function, a);
  PythonProgress progress(progress_arg);
  const CreatedFolders created({request.out, request.record_log});
  const bench::ScenarioRun run = CallInterruptibly(progress, created, [&] {
    bench::ScenarioRun done = bench::RunScenario(request, command, &progress);
    if (report && phases != bench::RunPhases::kTeachOnly) {
      bench::FinishOrWarn(
          "report.html", "report", done.out, [&] { bench::WriteHtmlReport(done.out); }, &progress);
    }
    return done;
  });
  return ToRunResult(run);
}

std::string ModeRepr(const ModeResult& m) {
  return "ModeResult(mode='" + m.mode + "', runs=" + std::to_string(m.runs) +
         ", successes=" + std::to_string(m.successes) + ")";
}

std::string RunRepr(const RunResult& r) {
  std::string modes;
  for (const auto& [name, mode] : r.modes) {
    const ModeResult& m = mode.cast<const ModeResult&>();
    modes += (modes.empty() ? "" : ", ") + m.mode + " " + std::to_string(m.successes) + "/" +
             std::to_string(m.runs);
  }
  return "RunResult(out='" + r.out.string() + "', modes=[" + modes +
         "], exit_code=" + std::to_string(r.exit_code) + ")";
}

void BindResultTypes(py::module_& m) {
  py::class_<ModeResult>(m, "ModeResult", "One map mode of a run.")
      .def_readonly("mode", &ModeResult::mode, "the mode's name")
      .def_readonly("runs", &ModeResult::runs, "playback runs (0: taught only)")
      .def_readonly("successes", &ModeResult::successes, "runs that reached the goal")
      .def_readonly("metrics", &ModeResult::metrics,
                    "the aggregate metrics, as in <mode>/metrics.json (None: taught only)")
      .def("__repr__", &ModeRepr);
  py::class_<RunResult>(m, "RunResult", "A run, teach or playback done and its folder written.")
      .def_readonly("out", &RunResult::out, "the results folder (pathlib.Path)")
      .def_readonly("exit_code", &RunResult::exit_code,
                    "the command line's: 1 when a run of a mode in limits.success_required "
                    "failed, else 0")
      .def_property_readonly(
          "success", [](const RunResult& r) { return r.exit_code == 0; },
          "every run of the modes that must succeed did")
      .def_readonly("summary", &RunResult::summary, "the table `retrace run` prints")
      .def_readonly("modes", &RunResult::modes, "{mode name: ModeResult}, in run order")
      .def("__repr__", &RunRepr);
}

}  // namespace

void BindRun(py::module_& m) {
  BindResultTypes(m);
  m.def(
      "run",
      [](const Path& scenario, py::object modes, py::object seed, py::object repeats,
         py::object set, const std::optional<Path>& out, py::object jobs, bool figures, bool report,
         bool video, int video_run, double video_speed, const std::optional<Path>& record_log,
         py::object progress) {
        const RunArguments a{scenario,   modes, seed,    repeats, set,       jobs,       out,
                             record_log, {},    figures, video,   video_run, video_speed};
        return Run(a, bench::RunPhases::kAll, report, progress, "run");
      },
      py::arg("scenario"), py::kw_only(), py::arg("modes") = py::none(),
      py::arg("seed") = py::none(), py::arg("repeats") = py::none(), py::arg("set") = py::none(),
      py::arg("out") = py::none(), py::arg("jobs") = 0, py::arg("figures") = true,
      py::arg("report") = true, py::arg("video") = false, py::arg("video_run") = 0,
      py::arg("video_speed") = 10.0, py::arg("record_log") = py::none(),
      py::arg("progress") = py::none(),
      "`retrace run`: teach the scenario's route, play it back in each map mode and write the "
      "results folder (default results/<scenario name>). modes: 'partial,consistent', a list, "
      "'all' or None (the scenario's); set: 'key=value', a list of them or a dict. Returns a "
      "RunResult.");
  m.def(
      "teach",
      [](const Path& scenario, py::object modes, py::object seed, py::object set,
         const std::optional<Path>& out, const std::optional<Path>& record_log,
         py::object progress) {
        const RunArguments a{scenario,   modes, seed, py::none(), set, py::int_(0), out,
                             record_log, {},    true, false,      0,   10.0};
        return Run(a, bench::RunPhases::kTeachOnly, false, progress, "teach");
      },
      py::arg("scenario"), py::kw_only(), py::arg("modes") = py::none(),
      py::arg("seed") = py::none(), py::arg("set") = py::none(), py::arg("out") = py::none(),
      py::arg("record_log") = py::none(), py::arg("progress") = py::none(),
      "`retrace teach`: drive the route once and write the teach folders only "
      "(<out>/<mode>/teach). Returns a RunResult whose modes have no runs.");
  m.def(
      "playback",
      [](const Path& scenario, const Path& teach, py::object mode, py::object seed,
         py::object repeats, py::object set, const std::optional<Path>& out, py::object jobs,
         bool figures, bool report, bool video, int video_run, double video_speed,
         py::object progress) {
        if (mode.is_none()) {
          const auto folder_mode = bench::TeachFolderMode(teach);
          mode = py::str(folder_mode ? std::string(core::EnumName(*folder_mode)) : "partial");
        }
        const RunArguments a{scenario, mode,  seed,    repeats, set,       jobs,       out,
                             {},       teach, figures, video,   video_run, video_speed};
        return Run(a, bench::RunPhases::kPlaybackOnly, report, progress, "playback");
      },
      py::arg("scenario"), py::arg("teach"), py::kw_only(), py::arg("mode") = py::none(),
      py::arg("seed") = py::none(), py::arg("repeats") = py::none(), py::arg("set") = py::none(),
      py::arg("out") = py::none(), py::arg("jobs") = 0, py::arg("figures") = true,
      py::arg("report") = true, py::arg("video") = false, py::arg("video_run") = 0,
      py::arg("video_speed") = 10.0, py::arg("progress") = py::none(),
      "`retrace playback`: play back the teach folder `teach` (<mode>/teach of an earlier run "
      "or teach) in the scenario's world. mode: the folder's (None: from its parent folder's "
      "name, else 'partial'). Returns a RunResult.");
}

}  // namespace retrace::python
