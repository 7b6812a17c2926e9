#pragma once
// The progress line of retrace.run(progress=None) and the other long calls: one line on
// sys.stderr, rewritten in place, as the command line draws it (bench/cli/progress.hpp); nothing
// when sys.stderr is not a terminal (a notebook, a pipe, CI). Used with the GIL held.

#include <pybind11/pybind11.h>

#include <string>

namespace retrace::python {

struct ProgressState;

class ProgressLine {
 public:
  /// Enabled when sys.stderr is a terminal.
  ProgressLine();
  /// "playback: 3/10 done, 120 s simulated, 95x real time", or for a countdown "sweep name
  /// [####----] 12/32 done".
  void Draw(const ProgressState& state);
  /// Clears the line (before a warning is printed, at the end).
  void Clear();

 private:
  void Write(const std::string& text);
  pybind11::object stderr_;
  bool enabled_ = false;
  bool drawn_ = false;
};

}  // namespace retrace::python
