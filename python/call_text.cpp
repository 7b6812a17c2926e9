#include "python/call_text.hpp"

namespace retrace::python {
namespace py = pybind11;

CallText::CallText(const std::string& function) : text_("retrace." + function + "(") {}

CallText& CallText::Positional(const std::filesystem::path& path) {
  text_ += (first_ ? "" : ", ") + std::string(py::repr(py::str(path.string())));
  first_ = false;
  return *this;
}

CallText& CallText::Keyword(const char* name, const py::handle& value) {
  if (value.is_none()) return *this;
  text_ += (first_ ? "" : ", ") + std::string(name) + "=" + std::string(py::repr(value));
  first_ = false;
  return *this;
}

CallText& CallText::Keyword(const char* name, const std::filesystem::path& path) {
  if (path.empty()) return *this;
  return Keyword(name, py::str(path.string()));
}

}  // namespace retrace::python
