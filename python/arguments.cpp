#include "python/arguments.hpp"

#include <cmath>
#include <limits>

#include "core/errors.hpp"

namespace retrace::python {
namespace py = pybind11;
namespace {

std::string TypeName(const py::handle& value) {
  return py::str(py::type::handle_of(value).attr("__name__"));
}

// An int, not a bool (True is an int in Python, and never meant as a count).
bool IsInt(const py::handle& value) {
  return py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value);
}

std::vector<std::string> SplitCommas(const std::string& text) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma - start));
    if (comma == std::string::npos) return parts;
    start = comma + 1;
  }
}

// Each element of a list, tuple or other non-str sequence as a str.
std::vector<std::string> Strings(const py::handle& value, const char* argument) {
  std::vector<std::string> out;
  for (const py::handle item : py::iter(value)) {
    if (!py::isinstance<py::str>(item))
      throw py::type_error(std::string(argument) + ": must hold str, got " + TypeName(item));
    out.push_back(item.cast<std::string>());
  }
  return out;
}

bool IsSequence(const py::handle& value) {
  return py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value);
}

}  // namespace

std::vector<std::string> NameList(const py::handle& value, const char* argument) {
  if (value.is_none()) return {};
  if (py::isinstance<py::str>(value)) return SplitCommas(value.cast<std::string>());
  if (IsSequence(value)) return Strings(value, argument);
  throw py::type_error(std::string(argument) + ": must be a str or a list of str, got " +
                       TypeName(value));
}

std::vector<std::string> Overrides(const py::handle& value) {
  if (value.is_none()) return {};
  if (py::isinstance<py::str>(value)) return {value.cast<std::string>()};
  if (IsSequence(value)) return Strings(value, "set");
  if (!py::isinstance<py::dict>(value)) {
    throw py::type_error("set: must be a 'key=value' str, a list of them or a dict, got " +
                         TypeName(value));
  }
  const py::object dumps = py::module_::import("json").attr("dumps");
  std::vector<std::string> out;
  for (const auto& [key, item] : value.cast<py::dict>()) {
    if (!py::isinstance<py::str>(key))
      throw py::type_error("set: keys must be str, got " + TypeName(key));
    const std::string text =
        py::isinstance<py::str>(item) ? item.cast<std::string>() : dumps(item).cast<std::string>();
    out.push_back(key.cast<std::string>() + "=" + text);
  }
  return out;
}

std::optional<std::uint64_t> Seed(const py::handle& value) {
  if (value.is_none()) return std::nullopt;
  if (!IsInt(value)) throw py::type_error("seed: must be an int, got " + TypeName(value));
  const py::int_ seed = value.cast<py::int_>();
  const py::int_ largest(std::numeric_limits<std::int64_t>::max());
  if (seed < py::int_(0) || seed > largest) {
    throw core::ConfigError("seed", "must be an integer from 0 to " +
                                        std::to_string(std::numeric_limits<std::int64_t>::max()) +
                                        ", got '" + std::string(py::str(value)) + "'");
  }
  return seed.cast<std::uint64_t>();
}

std::optional<int> BoundedInt(const py::handle& value, const char* argument, int minimum) {
  if (value.is_none()) return std::nullopt;
  if (!IsInt(value))
    throw py::type_error(std::string(argument) + ": must be an int, got " + TypeName(value));
  const py::int_ number = value.cast<py::int_>();
  const char* bound = minimum == 0 ? ">= 0" : "> 0";
  if (number < py::int_(minimum) || number > py::int_(std::numeric_limits<int>::max())) {
    throw core::ConfigError(argument, std::string("must be a number ") + bound + ", got '" +
                                          std::string(py::str(value)) + "'");
  }
  return number.cast<int>();
}

double PositiveNumber(double value, const char* argument) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw core::ConfigError(
        argument, "must be a number > 0, got '" + std::string(py::str(py::float_(value))) + "'");
  }
  return value;
}

}  // namespace retrace::python
