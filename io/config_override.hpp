#pragma once

#include <string>
#include <string_view>

namespace retrace::io {

/// One `--set a.b.c=value` override; value is parsed as YAML (so `[1, 2]` is a list).
/// List elements are addressed by index: `walls.2.thickness=0.3`.
struct ConfigOverride {
  std::string key_path;
  std::string value;
};

/// Parses "a.b.c=value". Throws core::ConfigError on a missing '=' or an empty key.
ConfigOverride ParseOverride(std::string_view text);

}  // namespace retrace::io
