#include "python/interruptible.hpp"

#include <chrono>
#include <exception>
#include <thread>

namespace retrace::python {
namespace py = pybind11;
namespace {

constexpr auto kPollPeriod = std::chrono::milliseconds(50);

// Hands the progress to Python until the work is over; the first exception Python raised (Ctrl-C,
// the callback's), after which the work is cancelled.
std::exception_ptr PollUntilOver(PythonProgress& progress) {
  std::exception_ptr raised;
  for (bool over = false; !over;) {
    {
      py::gil_scoped_release release;
      over = progress.Wait(kPollPeriod);
    }
    if (raised) continue;  // cancelled: only wait for the work to stop
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      progress.Deliver(over);
    } catch (...) {
      raised = std::current_exception();
      progress.Cancel();
    }
  }
  return raised;
}

}  // namespace

void RunInterruptibly(PythonProgress& progress, const CreatedFolders& created,
                      const std::function<void()>& work) {
  std::exception_ptr error;
  std::thread worker([&] {
    try {
      work();
    } catch (...) {
      error = std::current_exception();
    }
    progress.Finish();
  });
  const std::exception_ptr raised = PollUntilOver(progress);
  {
    py::gil_scoped_release release;
    worker.join();
  }
  progress.Close();
  if (raised || error) created.RemoveEmpty();
  if (raised) std::rethrow_exception(raised);
  if (error) std::rethrow_exception(error);
}

}  // namespace retrace::python
