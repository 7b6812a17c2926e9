#pragma once
// The message of the core::IoError a callable throws, for tests of readers' error messages:
//
//   EXPECT_NE(retrace::testing::IoErrorOf([&] { ReadTum(file); }).find("line 3"), npos);

#include <string>

#include "core/errors.hpp"

namespace retrace::testing {

/// The what() of the core::IoError `f()` throws, or "" if it throws none.
template <typename F>
std::string IoErrorOf(F&& f) {
  try {
    f();
  } catch (const core::IoError& e) {
    return e.what();
  }
  return "";
}

}  // namespace retrace::testing
