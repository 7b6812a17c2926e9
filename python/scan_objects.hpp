#pragma once
// retrace.Scan: one LiDAR scan as Python sees it, its ranges a read-only float32 NumPy array that
// views the scan's own memory (no copy; the array keeps the Scan alive).

#include <pybind11/pybind11.h>

#include <vector>

#include "core/laser_scan.hpp"

namespace retrace::python {

/// The scans as a list of retrace.Scan (each one copied once, into its Scan).
pybind11::list ScanList(const std::vector<core::LaserScan>& scans);

/// The scan a retrace.Scan holds; pybind11::cast_error (TypeError) for anything else.
const core::LaserScan& LaserScanOf(const pybind11::handle& scan);

/// Binds retrace.Scan.
void BindScan(pybind11::module_& m);

}  // namespace retrace::python
