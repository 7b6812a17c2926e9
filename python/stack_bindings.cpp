// Python stacks in every command (docs/PYTHON.md, "A Python stack in every command"):
// retrace.register_stack(name, factory, options=, summary=) registers a stack by name
// (bench/engine/stack_registry.hpp) whose runs call a Python object through the C++ stack
// interface (bench/stack/navigation_stack.hpp), so that retrace.run, compare and sweep, and the
// command line's scenarios run in this interpreter, drive it and score it as any C++ stack.
//
// The runs execute on the library's worker threads without the GIL; each call into Python takes
// it (a Python stack therefore runs one call at a time, whatever --jobs says). A Python
// exception inside the stack ends the run with a RuntimeError naming the stack and the method.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/engine/stack_registry.hpp"
#include "core/errors.hpp"
#include "python/bindings.hpp"
#include "python/native_stacks.hpp"
#include "python/scan_objects.hpp"
#include "python/stack_answer.hpp"
#include "python/taught_maps.hpp"

namespace retrace::python {
namespace py = pybind11;
namespace {

// A Python object kept alive from threads that may not hold the GIL: copied and destroyed only
// through the shared pointer, whose deleter takes the GIL.
using SharedObject = std::shared_ptr<py::object>;

SharedObject Share(py::object object) {
  return SharedObject(new py::object(std::move(object)), [](py::object* p) {
    const py::gil_scoped_acquire gil;
    delete p;
  });
}

class PythonStack final : public bench::NavigationStack {
 public:
  // With the GIL: looks for a native stack to look inside (python/native_stacks.hpp).
  PythonStack(std::string name, SharedObject stack, std::shared_ptr<bool> alive)
      : name_(std::move(name)),
        stack_(std::move(stack)),
        alive_(std::move(alive)),
        insight_(NativeInsight(*stack_)) {}
  ~PythonStack() override { *alive_ = false; }  // its native stacks refuse further calls
  PythonStack(const PythonStack&) = delete;
  PythonStack& operator=(const PythonStack&) = delete;

  void OnOdometry(double t, const core::OdometryDelta& d) override {
    Call("on_odometry", [&] { stack_->attr("on_odometry")(t, d.distance, d.dtheta); });
  }
  void OnScan(const core::LaserScan& scan) override {
    Call("on_scan", [&] { stack_->attr("on_scan")(ScanList({scan})[0]); });
  }
  bench::StackOutput OnControlTick(double t, double dt) override {
    bench::StackOutput out;
    Call("on_control_tick", [&] { out = Output(stack_->attr("on_control_tick")(t, dt)); });
    return out;
  }
  std::optional<bench::MapChange> Resume(bench::StackOutput* out) override {
    bool has = false;
    Call("resume", [&] {
      if (!py::hasattr(*stack_, "resume")) return;
      has = true;
      const bench::DriveCommand drive = out->drive;
      *out = Output(stack_->attr("resume")());
      out->drive = drive;  // the operator's command this tick
    });
    if (!has) return std::nullopt;
    return std::exchange(out->map_change, std::nullopt);
  }
  const bench::StackInsight* insight() const override { return insight_; }

 private:
  // Calls into Python with the GIL; a Python exception becomes one core::Error.
  template <class F>
  void Call(const char* method, F&& f) {
    const py::gil_scoped_acquire gil;
    try {
      f();
    } catch (py::error_already_set& e) {
      throw core::Error("stack '" + name_ + "', " + method + ": " + e.what());
    } catch (const py::cast_error& e) {
      throw core::ConfigError("answer", "stack '" + name_ + "', " + method +
                                            ": a value of the wrong type (" + e.what() + ")");
    }
  }

  // The answer of on_control_tick or resume (python/stack_answer.hpp); a change of map without
  // map_change is recorded as a change from the last estimate.
  bench::StackOutput Output(const py::object& answer) {
    bench::StackOutput out = StackAnswerOf(answer, "stack '" + name_ + "'");
    map_changes_.Apply(&out);
    return out;
  }

  std::string name_;
  SharedObject stack_;
  std::shared_ptr<bool> alive_;
  const bench::StackInsight* insight_;
  bench::MapChangeTracker map_changes_;
};

// What the factory is given: the taught maps, the robot, the run, the options and the maker of
// native stacks for this run.
py::dict ContextOf(const bench::StackContext& c, std::shared_ptr<const bool> alive) {
  py::dict d;
  d["native"] = NativeStackMaker(c, std::move(alive));
  d["maps"] = TaughtMapList(c.bundle);
  d["robot_radius"] = c.scenario.robot.radius;
  const core::Pose2& X_RL = c.scenario.robot.X_RL;
  d["lidar_mount"] = py::make_tuple(X_RL.x, X_RL.y, X_RL.theta);
  d["control_rate_hz"] = c.scenario.config.nav.control_rate_hz;
  d["run"] = c.run;
  d["seed"] = c.rng.seed();
  py::dict options;
  for (const auto& [k, v] : c.options) options[py::str(k)] = v;
  d["options"] = options;
  return d;
}

void RegisterPythonStack(const std::string& name, const py::object& factory,
                         const std::map<std::string, std::string>& options,
                         const std::string& summary) {
  if (!PyCallable_Check(factory.ptr())) {
    throw py::type_error("factory: a callable that takes the context and returns the stack");
  }
  bench::StackDescription d;
  d.name = name;
  d.summary = summary.empty() ? "a stack written in Python" : summary;
  for (const auto& [k, v] : options) d.options.push_back({k, v, ""});
  const SharedObject shared = Share(factory);
  d.make = [name, shared](const bench::StackContext& c) -> std::unique_ptr<bench::NavigationStack> {
    const py::gil_scoped_acquire gil;
    auto alive = std::make_shared<bool>(true);
    try {
      return std::make_unique<PythonStack>(name, Share((*shared)(ContextOf(c, alive))), alive);
    } catch (py::error_already_set& e) {
      throw core::Error("stack '" + name + "', factory: " + e.what());
    }
  };
  bench::RegisterStack(std::move(d));
}

}  // namespace

void BindStacks(py::module_& m) {
  m.def("register_stack", &RegisterPythonStack, py::arg("name"), py::arg("factory"), py::kw_only(),
        py::arg("options") = std::map<std::string, std::string>{}, py::arg("summary") = "",
        "Registers a navigation stack written in Python under `name`, for playback.stack in "
        "any scenario this interpreter runs (retrace.run, compare, sweep). factory(context) "
        "returns the stack for one run; context: {'maps' [TaughtMap], 'robot_radius', "
        "'lidar_mount', 'control_rate_hz', 'run', 'seed', 'options', 'native'}. The stack has "
        "on_odometry(t, distance, dtheta), on_scan(scan), on_control_tick(t, dt) -> {'v', "
        "'omega', 'estimate' (x, y, yaw) in map 'map''s frame, 'map', 'lost', 'off_map', "
        "'route_done', 'modified', 'blocked', 'emergency_stop', 'map_change'} (v, omega and "
        "estimate required) and optionally resume() -> the same, when an operator hands the "
        "robot back. context['native'](name) makes a registered C++ stack for the same run "
        "(NativeStack); kept as the stack's attribute 'native', the harness scores inside it. "
        "options: {name: default} of playback.stack_options it takes.");
  BindNativeStack(m);
  m.def("registered_stacks", &bench::RegisteredStacks, "The names playback.stack may take.");
}

}  // namespace retrace::python
