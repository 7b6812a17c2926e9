#pragma once
// Checks of command-line values with short messages (CLI11's own range checks print the largest
// double, 309 digits, as the upper bound).

#include <CLI/CLI.hpp>
#include <charconv>
#include <cstdint>
#include <limits>
#include <string>
#include <system_error>

namespace retrace::bench {

/// A number > 0 (integer or not).
inline const CLI::Validator kPositive(
    [](std::string& text) -> std::string {
      double v = 0.0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec != std::errc() || end != text.data() + text.size() || !(v > 0.0)) {
        return "must be a number > 0, got '" + text + "'";
      }
      return {};
    },
    "> 0");

/// A number >= 0.
inline const CLI::Validator kNonNegative(
    [](std::string& text) -> std::string {
      double v = 0.0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec != std::errc() || end != text.data() + text.size() || !(v >= 0.0)) {
        return "must be a number >= 0, got '" + text + "'";
      }
      return {};
    },
    ">= 0");

/// A seed: an integer from 0 to 2^63 - 1 (what scenario files hold). CLI11 would read "-1" into
/// an unsigned seed as 2^64 - 1.
inline const CLI::Validator kSeed(
    [](std::string& text) -> std::string {
      std::int64_t v = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec != std::errc() || end != text.data() + text.size() || v < 0) {
        return "must be an integer from 0 to " +
               std::to_string(std::numeric_limits<std::int64_t>::max()) + ", got '" + text + "'";
      }
      return {};
    },
    "0..2^63-1");

}  // namespace retrace::bench
