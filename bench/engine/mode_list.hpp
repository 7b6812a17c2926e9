#pragma once
// Map modes named by a user (`retrace run --mode`, `retrace compare --modes`), and the
// overrides a command line gives a scenario.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bench/engine/trace.hpp"
#include "io/config_override.hpp"

namespace retrace::bench {

/// Parses mode names, in the order given; `all` alone is every mode. Throws
/// core::ConfigError naming `option` when the list is empty, a name is not a mode, or a mode is
/// given twice.
std::vector<MapMode> ParseModeList(const std::vector<std::string>& names, std::string_view option);

/// The overrides a command line gives a scenario, in this order: every `--set` (a.b.c=value),
/// then `seed` and `playback.repeats` where given. Throws core::ConfigError for a malformed
/// `--set`.
std::vector<io::ConfigOverride> CommandLineOverrides(const std::vector<std::string>& sets,
                                                     std::optional<std::uint64_t> seed,
                                                     std::optional<int> repeats);

}  // namespace retrace::bench
