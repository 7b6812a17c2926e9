// retrace.sweep: `retrace sweep` as one library call (bench/sweep/sweep_run.hpp), interruptible
// (an interrupted sweep keeps the rows of its finished cases and resumes when called again, as
// the command line's does), and its SweepResult.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include "bench/output/html_report.hpp"
#include "bench/sweep/sweep_run.hpp"
#include "python/arguments.hpp"
#include "python/bindings.hpp"
#include "python/call_text.hpp"
#include "python/interruptible.hpp"
#include "python/table_columns.hpp"

namespace retrace::python {
namespace py = pybind11;
using Path = std::filesystem::path;
namespace {

/// What retrace.sweep returns.
struct SweepResult {
  Path out;
  std::string name;
  int cases = 0;      ///< of the shard (all of them, unsharded)
  int cases_run = 0;  ///< by this call; the others were done before
  double wall_time_s = 0.0;
  std::string summary;
  py::dict results;  ///< results.csv by column
};

SweepResult ToSweepResult(const bench::SweepRun& run) {
  const bench::SweepSpec& spec = run.spec;
  std::vector<std::vector<std::string>> rows;
  for (const bench::SweepRow& row : run.results) rows.push_back(row.fields);
  return {run.out,
          spec.name,
          static_cast<int>(run.shard_cases),
          static_cast<int>(run.cases_run),
          run.wall_time_s,
          bench::SweepRunSummary(run),
          TableColumns(bench::ResultsSchema(spec.parameters, spec.metrics).header, rows)};
}

SweepResult Sweep(const Path& file, const py::object& jobs, const std::optional<Path>& out,
                  const std::optional<std::string>& shard, const py::object& set, bool plot,
                  bool report, const py::object& progress_arg) {
  bench::SweepRequest request{file,
                              BoundedInt(jobs, "jobs", 0).value_or(0),
                              out.value_or(Path()),
                              shard.value_or(""),
                              Overrides(set),
                              plot};
  CallText call("sweep");
  call.Positional(file).Keyword("jobs", jobs).Keyword("out", request.out);
  if (shard) call.Keyword("shard", py::str(*shard));
  call.Keyword("set", set);
  PythonProgress progress(progress_arg);
  const CreatedFolders created({request.out});
  const bench::SweepRun run = CallInterruptibly(progress, created, [&] {
    bench::SweepRun done = bench::RunSweep(request, call.str(), &progress);
    if (report) {
      bench::FinishOrWarn(
          "report.html", "report", done.out, [&] { bench::WriteHtmlReport(done.out); }, &progress);
    }
    return done;
  });
  return ToSweepResult(run);
}

}  // namespace

void BindSweep(py::module_& m) {
  py::class_<SweepResult>(m, "SweepResult", "A sweep (or shard) done and its folder complete.")
      .def_readonly("out", &SweepResult::out, "the results folder (pathlib.Path)")
      .def_readonly("name", &SweepResult::name, "the sweep's name")
      .def_readonly("cases", &SweepResult::cases, "cases of the shard (all, unsharded)")
      .def_readonly("cases_run", &SweepResult::cases_run,
                    "cases run by this call (the others were done before: resumed)")
      .def_readonly("wall_time_s", &SweepResult::wall_time_s, "wall time of this call")
      .def_readonly("summary", &SweepResult::summary, "what `retrace sweep` prints")
      .def_readonly("results", &SweepResult::results,
                    "results.csv by column: {name: float64 array or list of str}")
      .def("__repr__", [](const SweepResult& r) {
        return "SweepResult(name='" + r.name + "', out='" + r.out.string() +
               "', cases=" + std::to_string(r.cases) + ")";
      });
  m.def("sweep", &Sweep, py::arg("file"), py::kw_only(), py::arg("jobs") = 0,
        py::arg("out") = py::none(), py::arg("shard") = py::none(), py::arg("set") = py::none(),
        py::arg("plot") = true, py::arg("report") = true, py::arg("progress") = py::none(),
        "`retrace sweep`: run every case of a sweep file in parallel, appending one row per case "
        "to <out>/results.csv (default results/sweeps/<name>); resumes a folder it was "
        "interrupted in. shard: 'i/N'. Returns a SweepResult.");
}

}  // namespace retrace::python
