// retrace's errors as Python exceptions, translated once for every binding (docs/PYTHON.md,
// "Errors"), each with the one line the command line prints after "retrace: error: ":
//
//   core::ConfigError            ValueError, with `key` the dotted key path or the argument it
//                                names (an option the library names, "--video-run", as Python's
//                                argument, "video_run"; the message keeps the option)
//   core::WorldError             ValueError (bad input: a robot in a wall, a blocked route)
//   core::IoError                FileNotFoundError when the file it names is missing, else OSError
//   core::Error (any other)      RuntimeError
//   core::Interrupted            KeyboardInterrupt
//   std::filesystem errors       FileNotFoundError, PermissionError or OSError by their errno
//
// str(exception) is the command line's line; the OSErrors carry no errno or filename (given
// them, Python would print "[Errno 2] ...: 'file'" instead).

#include "core/errors.hpp"

#include <cerrno>
#include <filesystem>
#include <string>
#include <string_view>

#include "python/bindings.hpp"

namespace retrace::python {
namespace py = pybind11;
namespace {

// Raises `type(message)` with the attributes set on the instance.
void RaiseWith(PyObject* type, const py::tuple& args, const py::dict& attributes) {
  py::object error = py::reinterpret_borrow<py::object>(type)(*args);
  for (const auto& [name, value] : attributes) error.attr(name) = value;
  PyErr_SetObject(type, error.ptr());
}

// The path an error message starts with ("<path>: ..." or "<path>:<line>: ..."), without its
// line and column.
std::string NamedPath(std::string_view message) {
  std::string_view path = message.substr(0, message.find(": "));
  for (int part = 0; part < 2; ++part) {  // line, then column
    const std::size_t colon = path.rfind(':');
    if (colon == std::string_view::npos || colon + 1 == path.size() ||
        path.find_first_not_of("0123456789", colon + 1) != std::string_view::npos)
      break;
    path = path.substr(0, colon);
  }
  return std::string(path);
}

// A missing file: the message says it could not be opened or found, and the path it names is
// not there.
bool NamesMissingFile(std::string_view message) {
  const bool says_missing = message.find("no such file") != std::string_view::npos ||
                            message.find("cannot open") != std::string_view::npos ||
                            message.find("does not exist") != std::string_view::npos;
  if (!says_missing) return false;
  const std::string path = NamedPath(message);
  std::error_code ec;
  return !path.empty() && !std::filesystem::exists(path, ec);
}

// The key of a ConfigError as Python spells it: a key path as it is; a command-line option that
// the library names ("--video-run", "--from") as the argument that gives it ("video_run",
// "from_s").
std::string PythonKey(const std::string& key) {
  if (!key.starts_with("--")) return key;
  std::string name = key.substr(2);
  for (char& c : name) c = c == '-' ? '_' : c;
  if (name == "from" || name == "to") name += "_s";
  return name;
}

void RaiseIoError(const core::IoError& e) {
  PyErr_SetString(NamesMissingFile(e.what()) ? PyExc_FileNotFoundError : PyExc_OSError, e.what());
}

void RaiseFilesystemError(const std::filesystem::filesystem_error& e) {
  const int code = e.code().category() == std::generic_category() ||
                           e.code().category() == std::system_category()
                       ? e.code().value()
                       : 0;
  PyObject* type = code == ENOENT                    ? PyExc_FileNotFoundError
                   : code == EACCES || code == EPERM ? PyExc_PermissionError
                                                     : PyExc_OSError;
  PyErr_SetString(type, e.what());
}

void Translate(std::exception_ptr error) {
  try {
    if (error) std::rethrow_exception(error);
  } catch (const core::ConfigError& e) {
    py::dict attributes;
    attributes["key"] = PythonKey(e.key_path());
    RaiseWith(PyExc_ValueError, py::make_tuple(e.what()), attributes);
  } catch (const core::WorldError& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  } catch (const core::IoError& e) {
    RaiseIoError(e);
  } catch (const core::Error& e) {
    PyErr_SetString(PyExc_RuntimeError, e.what());
  } catch (const core::Interrupted&) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
  } catch (const std::filesystem::filesystem_error& e) {
    RaiseFilesystemError(e);
  }
}

}  // namespace

void BindErrors(py::module_& /*m*/) { py::register_exception_translator(&Translate); }

}  // namespace retrace::python
