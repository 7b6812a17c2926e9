#pragma once
// A library call from Python that runs for seconds or hours: on a thread of its own, without the
// GIL, while the calling thread hands its progress to Python and checks for Ctrl-C
// (PyErr_CheckSignals) every 50 ms. Ctrl-C, or an exception raised by the progress callback or a
// warnings filter, cancels the call (ProgressSink::Cancelled: it stops at its next report and
// writes no results folder, bench/output/staged_folder.hpp), waits for it, removes the folders it
// created and raises that exception (KeyboardInterrupt) in Python. An error of the call is
// rethrown after the same cleanup (python/errors.cpp translates it).

#include <functional>
#include <optional>
#include <utility>

#include "python/created_folders.hpp"
#include "python/progress_sink.hpp"

namespace retrace::python {

/// Runs `work` as above. `work` must not touch Python. Needs the GIL.
void RunInterruptibly(PythonProgress& progress, const CreatedFolders& created,
                      const std::function<void()>& work);

/// RunInterruptibly for a call with a result.
template <class Work>
auto CallInterruptibly(PythonProgress& progress, const CreatedFolders& created, const Work& work) {
  std::optional<decltype(work())> result;
  RunInterruptibly(progress, created, [&] { result.emplace(work()); });
  return std::move(*result);
}

}  // namespace retrace::python
