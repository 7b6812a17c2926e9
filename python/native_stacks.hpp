#pragma once
// retrace.NativeStack: a registered C++ stack (retrace's navigator, say) made for the run a
// Python stack runs in, so that the Python stack can build on it: context["native"](name) in the
// factory of retrace.register_stack. Its methods are the Python stack interface's
// (on_odometry, on_scan, on_control_tick, resume), and its answers carry everything the C++
// interface answers (the command's flags, the exact map change), so that a Python stack that
// passes them on drives the run the C++ stack drives, to the bit. A Python stack that keeps it as
// its attribute `native` lets the harness look inside it (bench/engine/stack_insight.hpp): the
// dynamic-point scoring and the video, as for the C++ stack itself.

#include <pybind11/pybind11.h>

#include <memory>

#include "bench/engine/stack_registry.hpp"

namespace retrace::python {

/// The callable context["native"]: name → a retrace.NativeStack of that registered stack, with its
/// default options, for the run of `context` (same scenario, taught maps, run index and
/// randomness). Its stacks refuse every call once *alive is false (their run has ended).
pybind11::object NativeStackMaker(const bench::StackContext& context,
                                  std::shared_ptr<const bool> alive);

/// What the harness may look inside `stack` (a Python stack object) through its attribute `native`,
/// when that is a retrace.NativeStack; nullptr otherwise. Needs the GIL.
const bench::StackInsight* NativeInsight(const pybind11::object& stack);

/// Binds retrace.NativeStack.
void BindNativeStack(pybind11::module_& m);

}  // namespace retrace::python
