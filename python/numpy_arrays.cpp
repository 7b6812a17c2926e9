#include "python/numpy_arrays.hpp"

#include <utility>

#include "core/check.hpp"

namespace retrace::python {
namespace py = pybind11;
namespace {

template <class T>
py::array_t<T> MakeOwningArray(std::vector<T>&& values, const std::vector<py::ssize_t>& shape) {
  py::ssize_t count = 1;
  for (const py::ssize_t n : shape) count *= n;
  RETRACE_CHECK(static_cast<std::size_t>(count) == values.size());
  if (values.empty()) return py::array_t<T>(shape);  // no memory to own
  auto* owner = new std::vector<T>(std::move(values));
  const py::capsule base(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owner->data(), base);
}

}  // namespace

py::array_t<double> OwningArray(std::vector<double>&& values,
                                const std::vector<py::ssize_t>& shape) {
  return MakeOwningArray(std::move(values), shape);
}

py::array_t<std::uint8_t> OwningArray(std::vector<std::uint8_t>&& values,
                                      const std::vector<py::ssize_t>& shape) {
  return MakeOwningArray(std::move(values), shape);
}

}  // namespace retrace::python
