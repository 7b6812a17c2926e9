#include "python/native_stacks.hpp"

#include <optional>
#include <string>
#include <utility>

#include "bench/stack/navigation_stack.hpp"
#include "core/errors.hpp"
#include "python/scan_objects.hpp"

namespace retrace::python {
namespace py = pybind11;
namespace {

py::tuple PoseTuple(const core::Pose2& p) { return py::make_tuple(p.x, p.y, p.theta); }

// An answer as the Python stack interface gives it (python/stack_bindings.cpp reads it back).
py::dict AnswerOf(const bench::StackOutput& out, const std::optional<bench::MapChange>& change) {
  py::dict d;
  d["v"] = out.drive.command.v;
  d["omega"] = out.drive.command.omega;
  d["estimate"] = PoseTuple(out.X_MR);
  d["map"] = out.map;
  d["lost"] = out.lost;
  d["off_map"] = out.off_map;
  d["route_done"] = out.route_done;
  d["modified"] = out.drive.modified;
  d["blocked"] = out.drive.blocked;
  d["emergency_stop"] = out.drive.emergency_stop;
  if (change) {
    d["map_change"] = py::make_tuple(change->from, change->to, PoseTuple(change->X_MkR),
                                     PoseTuple(change->X_MnR));
  }
  return d;
}

class NativeStack {
 public:
  NativeStack(std::string name, std::unique_ptr<bench::NavigationStack> stack,
              std::shared_ptr<const bool> alive)
      : name_(std::move(name)), stack_(std::move(stack)), alive_(std::move(alive)) {}

  void OnOdometry(double t, double distance, double dtheta) {
    Live().OnOdometry(t, core::OdometryDelta{distance, dtheta});
  }
  void OnScan(const py::handle& scan) {
    const core::LaserScan& s = LaserScanOf(scan);
    bench::NavigationStack& stack = Live();
    const py::gil_scoped_release release;  // the localizer's update: other stacks may run
    stack.OnScan(s);
  }
  py::dict OnControlTick(double t, double dt) {
    bench::NavigationStack& stack = Live();
    {
      const py::gil_scoped_release release;
      last_ = stack.OnControlTick(t, dt);
    }
    return AnswerOf(last_, last_.map_change);
  }
  py::dict Resume() {
    const std::optional<bench::MapChange> change = Live().Resume(&last_);
    return AnswerOf(last_, change);
  }
  const bench::StackInsight* insight() const { return stack_->insight(); }

 private:
  bench::NavigationStack& Live() {
    if (!*alive_) {
      throw core::Error("native stack '" + name_ + "': the run it was made for has ended");
    }
    return *stack_;
  }

  std::string name_;
  std::unique_ptr<bench::NavigationStack> stack_;
  std::shared_ptr<const bool> alive_;
  bench::StackOutput last_;
};

}  // namespace

py::object NativeStackMaker(const bench::StackContext& context, std::shared_ptr<const bool> alive) {
  const bench::Scenario* scenario = &context.scenario;
  const nav::TeachBundle* bundle = &context.bundle;
  const int run = context.run;
  const core::Rng rng = context.rng;
  return py::cpp_function(
      [scenario, bundle, run, rng, alive](const std::string& name) {
        if (!*alive) throw core::Error("native stack '" + name + "': the run has ended");
        const bench::StackDescription& d = bench::FindStack(name);
        bench::StackContext c{*scenario, *bundle, run, rng, {}};
        for (const bench::StackOption& o : d.options) c.options[o.name] = o.default_value;
        return NativeStack(name, d.make(c), alive);
      },
      py::arg("name"));
}

const bench::StackInsight* NativeInsight(const py::object& stack) {
  if (!py::hasattr(stack, "native")) return nullptr;
  const py::object native = stack.attr("native");
  if (!py::isinstance<NativeStack>(native)) return nullptr;
  return native.cast<const NativeStack&>().insight();
}

void BindNativeStack(py::module_& m) {
  py::class_<NativeStack>(m, "NativeStack",
                          "A registered C++ stack inside a Python stack's run "
                          "(context['native'](name) in register_stack's factory).")
      .def("on_odometry", &NativeStack::OnOdometry, py::arg("t"), py::arg("distance"),
           py::arg("dtheta"))
      .def("on_scan", &NativeStack::OnScan, py::arg("scan"))
      .def("on_control_tick", &NativeStack::OnControlTick, py::arg("t"), py::arg("dt"),
           "{v, omega, estimate, map, lost, off_map, route_done, modified, blocked, "
           "emergency_stop[, map_change (from, to, X_MkR, X_MnR)]}")
      .def("resume", &NativeStack::Resume, "the same, after an operator handed the robot back");
}

}  // namespace retrace::python
