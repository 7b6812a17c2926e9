#include "python/scan_objects.hpp"

#include <pybind11/numpy.h>

#include <string>

#include "python/numpy_arrays.hpp"

namespace retrace::python {
namespace py = pybind11;
namespace {

struct Scan {
  core::LaserScan scan;
};

// The ranges of the Scan `self`, viewed, read-only.
py::array_t<float> RangesView(const py::object& self) {
  const Scan& s = self.cast<const Scan&>();
  py::array_t<float> ranges({static_cast<py::ssize_t>(s.scan.ranges.size())},
                            {static_cast<py::ssize_t>(sizeof(float))}, s.scan.ranges.data(), self);
  ranges.attr("flags").attr("writeable") = false;
  return ranges;
}

py::array_t<double> Angles(const Scan& s) {
  std::vector<double> angles;
  angles.reserve(s.scan.size());
  for (std::size_t i = 0; i < s.scan.size(); ++i) angles.push_back(s.scan.Angle(i));
  return OwningArray(std::move(angles), {static_cast<py::ssize_t>(s.scan.size())});
}

}  // namespace

py::list ScanList(const std::vector<core::LaserScan>& scans) {
  py::list list;
  for (const core::LaserScan& scan : scans) list.append(Scan{scan});
  return list;
}

const core::LaserScan& LaserScanOf(const py::handle& scan) { return scan.cast<const Scan&>().scan; }

void BindScan(py::module_& m) {
  py::class_<Scan>(m, "Scan", "One LiDAR scan, in the LiDAR frame L.")
      .def_property_readonly(
          "time", [](const Scan& s) { return s.scan.stamp; }, "s since the drive or run started")
      .def_property_readonly("ranges", &RangesView,
                             "(B,) float32, m; inf where the beam had no return (read-only)")
      .def_property_readonly("angles", &Angles, "(B,) float64: each beam's angle in L, rad")
      .def_property_readonly(
          "angle_min", [](const Scan& s) { return s.scan.angle_min; }, "rad: beam 0's angle")
      .def_property_readonly(
          "angle_increment", [](const Scan& s) { return s.scan.angle_increment; }, "rad")
      .def_property_readonly(
          "range_min", [](const Scan& s) { return s.scan.range_min; }, "m")
      .def_property_readonly(
          "range_max", [](const Scan& s) { return s.scan.range_max; }, "m")
      .def("__len__", [](const Scan& s) { return s.scan.size(); })
      .def("__repr__", [](const Scan& s) {
        return "Scan(time=" + std::to_string(s.scan.stamp) + ", " + std::to_string(s.scan.size()) +
               " beams)";
      });
}

}  // namespace retrace::python
