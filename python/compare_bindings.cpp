// retrace.compare: `retrace compare` as one library call (bench/compare/comparison_study.hpp),
// interruptible, and its ComparisonResult.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include "bench/compare/comparison_study.hpp"
#include "bench/output/html_report.hpp"
#include "io/json_writer.hpp"
#include "python/arguments.hpp"
#include "python/bindings.hpp"
#include "python/call_text.hpp"
#include "python/interruptible.hpp"
#include "python/json_to_python.hpp"

namespace retrace::python {
namespace py = pybind11;
using Path = std::filesystem::path;
namespace {

/// What retrace.compare returns.
struct ComparisonResult {
  Path out;
  std::string markdown;  ///< comparison.md, the table `retrace compare` prints
  py::object data;       ///< comparison.json
};

bench::ComparisonRequest CompareRequest(const Path& scenario, const py::object& modes,
                                        const py::object& stacks, const std::string& reference,
                                        const py::object& seeds, const py::object& repeats,
                                        const py::object& jobs, const std::optional<Path>& out,
                                        const py::object& set) {
  bench::ComparisonRequest request;
  request.scenario = scenario;
  if (!modes.is_none()) request.modes = NameList(modes, "modes");
  if (!stacks.is_none()) request.stacks = NameList(stacks, "stacks");
  request.reference = reference;
  request.seeds = BoundedInt(seeds, "seeds", 1).value_or(5);
  request.repeats = BoundedInt(repeats, "repeats", 1);
  request.jobs = BoundedInt(jobs, "jobs", 0).value_or(0);
  request.out = out.value_or(Path());
  request.overrides = Overrides(set);
  return request;
}

ComparisonResult Compare(const Path& scenario, const py::object& modes, const py::object& stacks,
                         const std::string& reference, const py::object& seeds,
                         const py::object& repeats, const py::object& jobs,
                         const std::optional<Path>& out, const py::object& set, bool report,
                         const py::object& progress_arg) {
  const bench::ComparisonRequest request =
      CompareRequest(scenario, modes, stacks, reference, seeds, repeats, jobs, out, set);
  CallText call("compare");
  call.Positional(scenario).Keyword("modes", modes).Keyword("stacks", stacks);
  call.Keyword("reference", py::str(reference));
  call.Keyword("seeds", seeds).Keyword("repeats", repeats).Keyword("jobs", jobs);
  call.Keyword("out", request.out).Keyword("set", set);
  PythonProgress progress(progress_arg);
  const CreatedFolders created({request.out});
  const bench::ComparisonStudy study = CallInterruptibly(progress, created, [&] {
    bench::ComparisonStudy done = bench::RunComparisonStudy(request, call.str(), &progress);
    if (report) {
      bench::FinishOrWarn(
          "report.html", "report", done.out, [&] { bench::WriteHtmlReport(done.out); }, &progress);
    }
    return done;
  });
  // What the folder holds (the study and its provenance), as load_results would read it.
  return {study.out, study.markdown, JsonToPython(io::ReadJsonFile(study.out / "comparison.json"))};
}

}  // namespace

void BindCompare(py::module_& m) {
  py::class_<ComparisonResult>(m, "ComparisonResult",
                               "A comparison study done, its folder written.")
      .def_readonly("out", &ComparisonResult::out, "the folder written (pathlib.Path)")
      .def_readonly("markdown", &ComparisonResult::markdown,
                    "comparison.md: the table `retrace compare` prints")
      .def_readonly("data", &ComparisonResult::data,
                    "comparison.json: per metric and mode the per-seed values, means, intervals "
                    "and the paired differences to the reference")
      .def("__repr__", [](const ComparisonResult& r) {
        return "ComparisonResult(out='" + r.out.string() + "')";
      });
  m.def("compare", &Compare, py::arg("scenario"), py::kw_only(), py::arg("modes") = py::none(),
        py::arg("stacks") = py::none(), py::arg("reference") = "consistent", py::arg("seeds") = 5, py::arg("repeats") = py::none(),
        py::arg("jobs") = 0, py::arg("out") = py::none(), py::arg("set") = py::none(),
        py::arg("report") = true, py::arg("progress") = py::none(),
        "`retrace compare`: the map modes over `seeds` scenario seeds (seed, seed + 1, ...; at "
        "least 2), paired, with 95 % confidence intervals, written to `out` (default "
        "results/compare/<scenario name>). modes: None or 'all' (every mode), a str or a list. "
        "stacks: playback.stack names to put side by side in every mode (a str or a list; "
        "None: the scenario's). Returns a ComparisonResult.");
}

}  // namespace retrace::python
