#pragma once
// The IEEE special values the tests feed in and expect back.

#include <limits>

namespace retrace::testing {

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace retrace::testing
