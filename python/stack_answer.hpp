#pragma once
// A Python stack's answer at a control tick, as both ways of driving a stack from Python give it:
// the dict a registered stack's on_control_tick (or resume) returns (python/stack_bindings.cpp),
// and the keywords of Episode.act (python/episode_bindings.cpp). One reading of one contract:
// bench::StackOutput (bench/stack/navigation_stack.hpp).

#include <pybind11/pybind11.h>

#include <string>

#include "bench/stack/navigation_stack.hpp"

namespace retrace::python {

/// The StackOutput of `answer`: {v, omega, estimate (x, y, yaw)} required; map, lost, off_map,
/// route_done, modified, blocked, emergency_stop and map_change ((from, to, X_MkR, X_MnR), which
/// must end in the answer's map) optional. `what` names the answerer in errors ("stack 'pp'").
/// Throws core::ConfigError("answer" or "estimate") for a malformed answer.
bench::StackOutput StackAnswerOf(const pybind11::handle& answer, const std::string& what);

/// A map_change (from, to, X_MkR, X_MnR) as a stack's answer gives it; throws
/// core::ConfigError("answer" or "estimate") for anything else.
bench::MapChange MapChangeOf(const pybind11::handle& value, const std::string& what);

}  // namespace retrace::python
