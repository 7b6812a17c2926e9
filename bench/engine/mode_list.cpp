#include "bench/engine/mode_list.hpp"

#include <algorithm>

#include "core/errors.hpp"

namespace retrace::bench {

std::vector<MapMode> ParseModeList(const std::vector<std::string>& names, std::string_view option) {
  const std::string where(option);
  if (names.empty()) {
    throw core::ConfigError(where, "no mode given; expected one or more of " +
                                       core::EnumNameList<MapMode>() +
                                       " (comma-separated), or all");
  }
  if (names == std::vector<std::string>{"all"}) {
    std::vector<MapMode> all;
    for (const auto& [mode, name] : core::EnumTraits<MapMode>::kNames) all.push_back(mode);
    return all;
  }
  std::vector<MapMode> modes;
  for (const std::string& name : names) {
    if (name == "all") throw core::ConfigError(where, "all means every mode; give it alone");
    const auto mode = core::ParseEnum<MapMode>(name);
    if (!mode) {
      throw core::ConfigError(where, "unknown mode '" + name + "'; expected one or more of " +
                                         core::EnumNameList<MapMode>() +
                                         " (comma-separated), or all");
    }
    if (std::find(modes.begin(), modes.end(), *mode) != modes.end()) {
      throw core::ConfigError(where, "mode '" + name + "' is given twice");
    }
    modes.push_back(*mode);
  }
  return modes;
}

std::vector<io::ConfigOverride> CommandLineOverrides(const std::vector<std::string>& sets,
                                                     std::optional<std::uint64_t> seed,
                                                     std::optional<int> repeats) {
  std::vector<io::ConfigOverride> overrides;
  for (const std::string& text : sets) overrides.push_back(io::ParseOverride(text));
  if (seed) overrides.push_back(io::ParseOverride("seed=" + std::to_string(*seed)));
  if (repeats)
    overrides.push_back(io::ParseOverride("playback.repeats=" + std::to_string(*repeats)));
  return overrides;
}

}  // namespace retrace::bench
