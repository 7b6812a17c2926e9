#pragma once
// The Python call as text, e.g. "retrace.run('scenarios/small.yaml', modes='partial', seed=3)":
// what a results folder's manifest records as its command, as the command line records its own.

#include <pybind11/pybind11.h>

#include <filesystem>
#include <string>

namespace retrace::python {

class CallText {
 public:
  /// `function` without the module ("run").
  explicit CallText(const std::string& function);
  /// The first, positional argument.
  CallText& Positional(const std::filesystem::path& path);
  /// name=repr(value); None is left out.
  CallText& Keyword(const char* name, const pybind11::handle& value);
  /// name='path'; an empty path is left out.
  CallText& Keyword(const char* name, const std::filesystem::path& path);
  /// "retrace.<function>(...)".
  std::string str() const { return text_ + ")"; }

 private:
  std::string text_;
  bool first_ = true;
};

}  // namespace retrace::python
