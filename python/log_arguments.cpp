#include "python/log_arguments.hpp"

#include <utility>

#include "python/arguments.hpp"

namespace retrace::python {
namespace py = pybind11;
using Path = std::filesystem::path;

logs::StreamChoice StreamChoiceOf(const StreamArguments& streams) {
  logs::StreamChoice choice;
  choice.scan_topic = streams.scan_topic;
  choice.odometry_topic = streams.odometry_topic;
  choice.reference_topic = streams.reference_topic;
  choice.odom_frame = streams.odom_frame;
  choice.base_frame = streams.base_frame;
  return choice;
}

bench::LogRunOptions LogRunOptionsOf(const LogArguments& a) {
  bench::LogRunOptions options;
  options.log = a.log;
  options.out = a.out.value_or(Path());
  if (a.from_s) options.window.from_s = *a.from_s;
  if (a.to_s) options.window.to_s = *a.to_s;
  options.synthetic_odometry = a.synthetic_odometry;
  options.reference = a.reference;
  options.config = a.config;
  options.overrides = Overrides(a.set);
  options.seed = Seed(a.seed);
  options.figures = a.figures;
  options.streams = StreamChoiceOf(a.streams);
  return options;
}

CallText LogCallText(const char* function, const LogArguments& a) {
  CallText call(function);
  call.Positional(a.log).Keyword("out", a.out.value_or(Path()));
  if (a.from_s) call.Keyword("from_s", py::float_(*a.from_s));
  if (a.to_s) call.Keyword("to_s", py::float_(*a.to_s));
  if (a.synthetic_odometry) call.Keyword("synthetic_odometry", py::bool_(true));
  call.Keyword("reference", a.reference.value_or(Path()));
  call.Keyword("config", a.config.value_or(Path())).Keyword("set", a.set).Keyword("seed", a.seed);
  const StreamArguments& s = a.streams;
  const std::pair<const char*, std::string> topics[] = {{"scan_topic", s.scan_topic},
                                                        {"odometry_topic", s.odometry_topic},
                                                        {"reference_topic", s.reference_topic},
                                                        {"base_frame", s.base_frame}};
  for (const auto& [name, value] : topics) {
    if (!value.empty()) call.Keyword(name, py::str(value));
  }
  if (s.odom_frame != "odom") call.Keyword("odom_frame", py::str(s.odom_frame));
  return call;
}

}  // namespace retrace::python
