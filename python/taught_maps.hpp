#pragma once
// The taught maps of a bundle as Python sees them: a list of retrace.TaughtMap (bound by
// python/episode_bindings.cpp), each map's grid, path and switch pose in its own frame.

#include <pybind11/pybind11.h>

namespace retrace::nav {
struct TeachBundle;
}

namespace retrace::python {

pybind11::list TaughtMapList(const nav::TeachBundle& bundle);

}  // namespace retrace::python
