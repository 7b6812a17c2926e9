#pragma once
// The key path a config's Validate() names, for tests that check every bad value is reported
// under the right key:
//
//   LidarConfig c;
//   c.beams = 0;
//   EXPECT_EQ(retrace::testing::ValidationErrorKey(c), "beams");
//   EXPECT_EQ(retrace::testing::ValidationErrorKey<LidarConfig>([](auto& c) { c.beams = 0; }),
//             "beams");
//   EXPECT_EQ(retrace::testing::ValidationErrorKey(LidarConfig{}), retrace::testing::kValid);

#include <concepts>
#include <string>
#include <string_view>

#include "core/errors.hpp"

namespace retrace::testing {

/// What ValidationErrorKey returns when Validate() does not throw.
inline constexpr std::string_view kValid = "<valid>";

/// Calls config.Validate() and returns the key path of the ConfigError it throws, or "<valid>"
/// (kValid) when it does not throw. Other exceptions propagate.
template <class Config>
std::string ValidationErrorKey(const Config& config) {
  try {
    config.Validate();
  } catch (const core::ConfigError& e) {
    return e.key_path();
  }
  return std::string(kValid);
}

/// Default-constructs a Config, applies edit(config) and returns ValidationErrorKey of it.
template <class Config, std::invocable<Config&> Edit>
std::string ValidationErrorKey(Edit edit) {
  Config config;
  edit(config);
  return ValidationErrorKey(config);
}

}  // namespace retrace::testing
