#pragma once
// The Python arguments of the library calls checked and turned into what the requests hold, with
// the command line's messages (a wrong value: core::ConfigError naming the argument, ValueError
// in Python; a wrong type: TypeError), so that misuse never reaches the library.

#include <pybind11/pybind11.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace retrace::python {

/// A list of names: None (empty), a str (comma-separated, as `--mode a,b` takes them) or a
/// sequence of str. Throws pybind11::type_error naming `argument` for anything else.
std::vector<std::string> NameList(const pybind11::handle& value, const char* argument);

/// The overrides of `set`: None (none), a "key.path=value" str, a sequence of them, or a dict
/// {"key.path": value} whose values are YAML text when they are str and JSON (numbers, bools,
/// lists, None) otherwise. Throws pybind11::type_error for anything else.
std::vector<std::string> Overrides(const pybind11::handle& value);

/// A seed: None, or an int from 0 to 2^63 - 1. Throws core::ConfigError("seed") out of range,
/// pybind11::type_error for a non-int.
std::optional<std::uint64_t> Seed(const pybind11::handle& value);

/// An optional int >= `minimum` (None: none). Throws core::ConfigError naming `argument` with
/// the command line's "must be a number > 0" or ">= 0", pybind11::type_error for a non-int.
std::optional<int> BoundedInt(const pybind11::handle& value, const char* argument, int minimum);

/// A number > 0. Throws core::ConfigError naming `argument`.
double PositiveNumber(double value, const char* argument);

}  // namespace retrace::python
