#pragma once
// Config reflection. Every component has a plain `XConfig` struct with defaults in its member
// initialisers, a `Reflect(v)` that names its fields, and optionally a `Validate()` that throws
// ConfigError naming the offending key (relative to the struct). `io/config_yaml.hpp` reads
// and writes any such struct strictly (unknown keys are errors). Example:
//
//   struct LidarConfig {
//     double fov_deg = 270.0;
//     int beams = 1081;
//     template <class V> void Reflect(V& v) { v("fov_deg", fov_deg); v("beams", beams); }
//     void Validate() const { RequireInRange("fov_deg", fov_deg, 0.0, 360.0); }
//   };
//
// Supported field types: bool, integers, double, std::string, named enums (EnumTraits below),
// core::Vec2 ([x, y]), core::Pose2 ([x, y, theta]), std::array<double, N>, std::vector<T>,
// std::optional<T>, std::map<std::string, std::string> (a mapping of scalars, each kept as its
// text) and nested reflectable structs.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <concepts>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "core/errors.hpp"

namespace retrace::core {

/// Specialise with `static constexpr std::array<std::pair<E, std::string_view>, N> kNames`
/// to make an enum readable from and writable to config files by name.
template <class E>
struct EnumTraits;

template <class E>
concept NamedEnum = std::is_enum_v<E> && requires {
  EnumTraits<E>::kNames;
};

template <NamedEnum E>
std::string_view EnumName(E value) {
  for (const auto& [e, name] : EnumTraits<E>::kNames) {
    if (e == value) return name;
  }
  return "?";
}

template <NamedEnum E>
std::optional<E> ParseEnum(std::string_view name) {
  for (const auto& [e, n] : EnumTraits<E>::kNames) {
    if (n == name) return e;
  }
  return std::nullopt;
}

template <NamedEnum E>
std::string EnumNameList() {
  std::string out;
  for (const auto& [e, n] : EnumTraits<E>::kNames) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

/// A config value that may instead be one of the words of the named enum E, for the program to
/// decide how (e.g. `route.switch_points: auto` or `online`). Files hold either a word or a T.
template <NamedEnum E, class T>
struct WordOr {
  std::optional<E> word;  ///< the word given; nullopt: `value` was given
  T value{};

  bool is(E w) const { return word == w; }
};
template <class T>
struct IsWordOr : std::false_type {};
template <NamedEnum E, class T>
struct IsWordOr<WordOr<E, T>> : std::true_type {};

/// A visitor that does nothing; used to detect reflectable structs.
struct NullVisitor {
  template <class T>
  void operator()(std::string_view, T&) {}
};

template <class T>
concept Reflectable = std::is_class_v<T> && requires(T& t, NullVisitor& v) {
  t.Reflect(v);
};

template <class T>
concept Validatable = requires(const T& t) {
  t.Validate();
};

/// Shortest decimal text that reads back as the same double ("0.1", "-1", "2.5e-05").
inline std::string FormatNumber(double v) {
  char buf[32];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  return ec == std::errc() ? std::string(buf, ptr) : std::string("?");
}

// Validation helpers for Validate() implementations; each throws ConfigError(key, ...).
inline void RequireFinite(std::string_view key, double v) {
  if (!std::isfinite(v)) throw ConfigError(std::string(key), "must be a finite number");
}
inline void RequirePositive(std::string_view key, double v) {
  if (!(v > 0.0) || !std::isfinite(v)) {
    throw ConfigError(std::string(key), "must be > 0, got " + FormatNumber(v));
  }
}
inline void RequireNonNegative(std::string_view key, double v) {
  if (!(v >= 0.0) || !std::isfinite(v)) {
    throw ConfigError(std::string(key), "must be >= 0, got " + FormatNumber(v));
  }
}
inline void RequireInRange(std::string_view key, double v, double lo, double hi) {
  if (!(v >= lo && v <= hi)) {
    throw ConfigError(std::string(key), "must be in [" + FormatNumber(lo) + ", " +
                                            FormatNumber(hi) + "], got " + FormatNumber(v));
  }
}
inline void RequireIntInRange(std::string_view key, long long v, long long lo, long long hi) {
  if (v < lo || v > hi) {
    throw ConfigError(std::string(key), "must be in [" + std::to_string(lo) + ", " +
                                            std::to_string(hi) + "], got " + std::to_string(v));
  }
}
/// Requires v > other, where other is the value of the key named other_key.
inline void RequireGreater(std::string_view key, double v, std::string_view other_key,
                           double other) {
  if (!(v > other)) {
    throw ConfigError(std::string(key), "must be greater than " + std::string(other_key) + " (" +
                                            FormatNumber(other) + "), got " + FormatNumber(v));
  }
}

/// Levenshtein distance, for "did you mean" suggestions.
inline std::size_t EditDistance(std::string_view a, std::string_view b) {
  std::string_view s = a, t = b;
  std::size_t prev_diag = 0;
  std::basic_string<std::size_t> row(t.size() + 1, 0);
  for (std::size_t j = 0; j <= t.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= s.size(); ++i) {
    prev_diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= t.size(); ++j) {
      const std::size_t old = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, prev_diag + (s[i - 1] == t[j - 1] ? 0 : 1)});
      prev_diag = old;
    }
  }
  return row[t.size()];
}

}  // namespace retrace::core
