#pragma once
// The source tree, for tests that read the shipped scenarios, worlds, suites and test data.
// RETRACE_SOURCE_DIR is defined for every test executable by tests/CMakeLists.txt.

#include <filesystem>

namespace retrace::testing {

// Inside functions only: a variable at namespace scope is built from RETRACE_SOURCE_DIR itself.
// Clang 14 may initialize an inline variable after the other variables of the same file (seen at
// -O0), and kSource would still be empty there.
inline const std::filesystem::path kSource = RETRACE_SOURCE_DIR;

}  // namespace retrace::testing
