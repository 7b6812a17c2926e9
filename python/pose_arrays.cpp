#include "python/pose_arrays.hpp"

#include "python/numpy_arrays.hpp"

namespace retrace::python {
namespace py = pybind11;

py::array_t<double> PoseArray(const std::vector<io::StampedPose>& poses) {
  std::vector<double> values;
  values.reserve(poses.size() * 4);
  for (const io::StampedPose& p : poses) {
    values.insert(values.end(), {p.t, p.pose.x, p.pose.y, p.pose.theta});
  }
  return OwningArray(std::move(values), {static_cast<py::ssize_t>(poses.size()), 4});
}

py::array_t<double> PathArray(const core::Path& path) {
  std::vector<double> values;
  values.reserve(path.size() * 3);
  for (const core::Pose2& p : path.poses()) values.insert(values.end(), {p.x, p.y, p.theta});
  return OwningArray(std::move(values), {static_cast<py::ssize_t>(path.size()), 3});
}

}  // namespace retrace::python
