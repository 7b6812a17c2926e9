#pragma once
// NumPy arrays that own the C++ memory they view: the vector moves into a capsule that is the
// array's base, so nothing is copied and the memory lives as long as the array (or any view).

#include <pybind11/numpy.h>

#include <cstdint>
#include <vector>

namespace retrace::python {

/// `values` (row-major) as an array of `shape`; values.size() must be the product of shape.
pybind11::array_t<double> OwningArray(std::vector<double>&& values,
                                      const std::vector<pybind11::ssize_t>& shape);
pybind11::array_t<std::uint8_t> OwningArray(std::vector<std::uint8_t>&& values,
                                            const std::vector<pybind11::ssize_t>& shape);

}  // namespace retrace::python
