#pragma once
// Map modes named on the command line (`retrace run --mode`, `retrace compare --modes`).

#include <string>
#include <string_view>
#include <vector>

#include "bench/engine/trace.hpp"

namespace retrace::bench {

/// Parses mode names, in the order given; `all` alone is every mode. Throws
/// core::ConfigError naming `option` when the list is empty, a name is not a mode, or a mode is
/// given twice.
std::vector<MapMode> ParseModeList(const std::vector<std::string>& names, std::string_view option);

}  // namespace retrace::bench
