// The extension module `retrace._retrace`: retrace's library calls for Python (docs/PYTHON.md).
// The package python/retrace/ re-exports it with the results loader around it.

#include <pybind11/pybind11.h>

#include "python/bindings.hpp"

PYBIND11_MODULE(_retrace, m) {
  m.doc() =
      "retrace: teaching-playback navigation without a consistent map, simulated. The library "
      "calls of the `retrace` program (run, teach, playback, sweep, compare, the log commands) "
      "and readers of the files they write.";
  m.attr("__version__") = RETRACE_VERSION;
  retrace::python::BindErrors(m);
  retrace::python::BindProgress(m);
  retrace::python::BindRun(m);
  retrace::python::BindSweep(m);
  retrace::python::BindCompare(m);
  retrace::python::BindLogs(m);
  retrace::python::BindLogInfo(m);
  retrace::python::BindEpisodes(m);
  retrace::python::BindStacks(m);
  retrace::python::BindResults(m);
}
