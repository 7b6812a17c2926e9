#pragma once
// The source tree, for tests that read the shipped scenarios, worlds, suites and test data.
// RETRACE_SOURCE_DIR is defined for every test executable by tests/CMakeLists.txt.

#include <filesystem>

namespace retrace::testing {

inline const std::filesystem::path kSource = RETRACE_SOURCE_DIR;

}  // namespace retrace::testing
