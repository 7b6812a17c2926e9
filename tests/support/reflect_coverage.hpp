#pragma once
// Checks that a config struct's Reflect() names every one of its fields — a field left out of
// Reflect() would be neither read from YAML nor written into manifests, silently. C++ has no
// field list to compare with, so the check uses the layout: the fields that Reflect() visits,
// sorted by offset, must tile the struct, the only gaps being the padding the compiler must put
// before a field to align it (and at the end). A field missing from Reflect() leaves a gap
// larger than that. Nested reflectable structs (also inside std::vector and std::optional) are
// checked too, each by a default-constructed value.
//
// Limitation: a missing field small enough to fit into padding that the fields around it need
// anyway (a bool between a bool and an int) cannot be seen from the layout.
//
//   EXPECT_EQ(retrace::testing::UnreflectedBytes<ScenarioConfig>(), "");

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/config.hpp"

namespace retrace::testing {

namespace internal {

template <class T>
struct IsVector : std::false_type {};
template <class T, class A>
struct IsVector<std::vector<T, A>> : std::true_type {
  using Element = T;
};
template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {
  using Element = T;
};

template <class T>
std::string Check(std::string_view name);

// Records where each reflected field lies, and checks nested reflectable types.
struct FieldLayout {
  struct Field {
    std::size_t begin;
    std::size_t end;
    std::size_t align;
    std::string name;
  };
  const std::byte* base;
  std::string prefix;
  std::vector<Field> fields;
  std::string problem;

  template <class F>
  void operator()(std::string_view key, F& field) {
    const auto begin = static_cast<std::size_t>(reinterpret_cast<const std::byte*>(&field) - base);
    fields.push_back({begin, begin + sizeof(F), alignof(F), std::string(key)});
    const std::string name = prefix + std::string(key);
    std::string nested;
    if constexpr (core::Reflectable<F>) {
      nested = Check<F>(name);
    } else if constexpr (IsVector<F>::value) {
      if constexpr (core::Reflectable<typename IsVector<F>::Element>)
        nested = Check<typename IsVector<F>::Element>(name + "[]");
    } else if constexpr (IsOptional<F>::value) {
      if constexpr (core::Reflectable<typename IsOptional<F>::Element>)
        nested = Check<typename IsOptional<F>::Element>(name);
    }
    if (problem.empty()) problem = nested;
  }
};

inline std::size_t RoundUp(std::size_t n, std::size_t align) {
  return (n + align - 1) / align * align;
}

template <class T>
std::string Check(std::string_view name) {
  T value{};
  FieldLayout layout{reinterpret_cast<const std::byte*>(&value),
                     name.empty() ? std::string() : std::string(name) + ".",
                     {},
                     {}};
  value.Reflect(layout);
  if (!layout.problem.empty()) return layout.problem;
  std::vector<FieldLayout::Field>& f = layout.fields;
  std::sort(f.begin(), f.end(), [](const auto& a, const auto& b) { return a.begin < b.begin; });
  const std::string where = name.empty() ? std::string("the struct") : std::string(name);
  std::size_t end = 0;
  for (const FieldLayout::Field& field : f) {
    if (field.begin < end)
      return where + ": field '" + field.name + "' is visited twice or overlaps";
    if (field.begin != RoundUp(end, field.align)) {
      return where + ": bytes " + std::to_string(end) + ".." + std::to_string(field.begin) +
             " before '" + field.name + "' hold a field that Reflect() does not name";
    }
    end = field.end;
  }
  if (RoundUp(end, alignof(T)) != sizeof(T)) {
    return where + ": bytes " + std::to_string(end) + ".." + std::to_string(sizeof(T)) +
           " at the end hold a field that Reflect() does not name";
  }
  return "";
}

}  // namespace internal

/// "" when Reflect() of T (and of every reflectable struct inside it) names every field;
/// otherwise where the first unnamed bytes are.
template <core::Reflectable T>
std::string UnreflectedBytes() {
  return internal::Check<T>("");
}

}  // namespace retrace::testing
