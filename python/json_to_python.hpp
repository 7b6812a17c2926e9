#pragma once
// JSON (metrics.json, comparison.json, what the metrics' ToJson gives) as Python values: objects
// as dict, arrays as list, numbers as int or float, null as None.

#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace retrace::python {

pybind11::object JsonToPython(const nlohmann::json& value);

}  // namespace retrace::python
