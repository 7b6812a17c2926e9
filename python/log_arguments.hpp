#pragma once
// The arguments the log calls share (the command line's shared log options,
// bench/replay/log_run_options.hpp), as Python gave them, checked into LogRunOptions.

#include <pybind11/pybind11.h>

#include <filesystem>
#include <optional>
#include <string>

#include "bench/replay/log_run_options.hpp"
#include "python/call_text.hpp"

namespace retrace::python {

/// scan_topic, odometry_topic, reference_topic, odom_frame, base_frame (empty: automatic).
struct StreamArguments {
  std::string scan_topic, odometry_topic, reference_topic, odom_frame = "odom", base_frame;
};

struct LogArguments {
  std::filesystem::path log;
  std::optional<std::filesystem::path> out;
  std::optional<double> from_s, to_s;  ///< s since the log's first scan
  bool synthetic_odometry = false;
  std::optional<std::filesystem::path> reference, config;
  pybind11::object set, seed;
  bool figures = true;
  StreamArguments streams;
};

logs::StreamChoice StreamChoiceOf(const StreamArguments& streams);

/// The library's options; throws like the command line for a bad seed or override.
bench::LogRunOptions LogRunOptionsOf(const LogArguments& a);

/// "retrace.<function>(<log>, out=..., ...)" with the shared arguments given; the caller adds
/// its own.
CallText LogCallText(const char* function, const LogArguments& a);

}  // namespace retrace::python
