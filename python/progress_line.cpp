#include "python/progress_line.hpp"

#include <algorithm>
#include <cstdio>

#include "bench/engine/progress.hpp"
#include "python/progress_sink.hpp"

namespace retrace::python {
namespace py = pybind11;
namespace {

std::string CountdownText(const ProgressState& state) {
  constexpr int kWidth = 24;
  const int filled =
      state.total > 0 ? std::clamp(state.done, 0, state.total) * kWidth / state.total : 0;
  std::string bar = "[";
  bar.append(static_cast<std::size_t>(filled), '#');
  bar.append(static_cast<std::size_t>(kWidth - filled), '-');
  bar += ']';
  return state.phase + " " + bar + " " + std::to_string(state.done) + "/" +
         std::to_string(state.total) + " done, " + bench::FormatDuration(state.elapsed_s) +
         " so far";
}

std::string PhaseText(const ProgressState& state) {
  char text[128];
  std::snprintf(text, sizeof(text), ": %d/%d done, %.0f s simulated, %.0fx real time", state.done,
                state.total, state.sim_time_s,
                state.elapsed_s > 0.0 ? state.sim_time_s / state.elapsed_s : 0.0);
  return state.phase + text;
}

}  // namespace

ProgressLine::ProgressLine() : stderr_(py::module_::import("sys").attr("stderr")) {
  try {
    enabled_ = !stderr_.is_none() && stderr_.attr("isatty")().cast<bool>();
  } catch (const py::error_already_set&) {
    enabled_ = false;  // a stand-in stderr without isatty
  }
}

void ProgressLine::Draw(const ProgressState& state) {
  if (!enabled_) return;
  Write("\r\033[K" + (state.countdown ? CountdownText(state) : PhaseText(state)));
  drawn_ = true;
}

void ProgressLine::Clear() {
  if (!enabled_ || !drawn_) return;
  Write("\r\033[K");
  drawn_ = false;
}

void ProgressLine::Write(const std::string& text) {
  stderr_.attr("write")(text);
  stderr_.attr("flush")();
}

}  // namespace retrace::python
