#include "python/stack_answer.hpp"

#include <pybind11/stl.h>

#include <cstddef>
#include <vector>

#include "core/errors.hpp"

namespace retrace::python {
namespace py = pybind11;
namespace {

// (x, y, yaw) from a Python sequence, or a ConfigError naming what was given.
core::Pose2 PoseOf(const py::handle& value, const std::string& what) {
  std::vector<double> v;
  try {
    v = value.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    throw core::ConfigError("estimate", what + " returned an estimate that is not (x, y, yaw)");
  }
  if (v.size() != 3) {
    throw core::ConfigError("estimate", what + " returned an estimate of " +
                                            std::to_string(v.size()) + " numbers, not (x, y, yaw)");
  }
  return {v[0], v[1], v[2]};
}

}  // namespace

bench::MapChange MapChangeOf(const py::handle& value, const std::string& what) {
  py::tuple t;
  try {
    t = value.cast<py::tuple>();
  } catch (const py::cast_error&) {
  }
  if (t.size() != 4) {
    throw core::ConfigError("answer", what +
                                          " answered a map_change that is not (from, to, "
                                          "X_MkR, X_MnR)");
  }
  return {t[0].cast<std::size_t>(), t[1].cast<std::size_t>(), PoseOf(t[2], what),
          PoseOf(t[3], what)};
}

bench::StackOutput StackAnswerOf(const py::handle& answer, const std::string& what) {
  if (!py::isinstance<py::dict>(answer)) {
    throw core::ConfigError("answer", what +
                                          " must answer with a dict {v, omega, estimate, "
                                          "map, lost, route_done}");
  }
  const py::dict d = py::reinterpret_borrow<py::dict>(answer);
  for (const char* key : {"v", "omega", "estimate"}) {
    if (!d.contains(key)) {
      throw core::ConfigError(
          "answer", what + " answered without '" + key + "': {v, omega, estimate} are required");
    }
  }
  const auto flag = [&d](const char* key) { return d.contains(key) && d[key].cast<bool>(); };
  bench::StackOutput out;
  out.drive.command = {d["v"].cast<double>(), d["omega"].cast<double>()};
  out.X_MR = PoseOf(d["estimate"], what);
  out.map = d.contains("map") ? d["map"].cast<std::size_t>() : 0;
  out.lost = flag("lost");
  out.off_map = flag("off_map");
  out.route_done = flag("route_done");
  out.drive.modified = flag("modified");
  out.drive.blocked = flag("blocked");
  out.drive.emergency_stop = flag("emergency_stop");
  if (d.contains("map_change") && !d["map_change"].is_none()) {
    out.map_change = MapChangeOf(d["map_change"], what);
    if (out.map_change->to != out.map) {
      throw core::ConfigError("answer", what + " answered a map_change into map " +
                                            std::to_string(out.map_change->to) + " in map " +
                                            std::to_string(out.map));
    }
  }
  return out;
}

}  // namespace retrace::python
