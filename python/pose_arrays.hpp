#pragma once
// Trajectories and paths as NumPy arrays, one pose a row: (N, 4) [t, x, y, yaw] for stamped
// poses (a TUM file projected on the plane), (N, 3) [x, y, yaw] for paths (m, m, rad).

#include <pybind11/numpy.h>

#include <vector>

#include "core/path.hpp"
#include "io/tum.hpp"

namespace retrace::python {

pybind11::array_t<double> PoseArray(const std::vector<io::StampedPose>& poses);
pybind11::array_t<double> PathArray(const core::Path& path);

}  // namespace retrace::python
