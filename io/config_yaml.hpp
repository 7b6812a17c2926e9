#pragma once
// Strict YAML reading and writing of reflectable config structs (core/config.hpp).
// Unknown keys, wrong types, NaN/inf and values rejected by Validate() are ConfigErrors whose
// message names the file, the line, the key path and, for unknown keys, the nearest valid key.

#include <yaml-cpp/yaml.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/config.hpp"
#include "core/errors.hpp"
#include "core/pose2.hpp"
#include "io/config_override.hpp"

namespace retrace::io {

/// Loads a YAML file. Throws IoError if it cannot be read, ConfigError (with line) if it is
/// not valid YAML.
YAML::Node LoadYamlFile(const std::filesystem::path& file);

/// Writes each override into the node tree, creating maps on the way. List elements are
/// addressed by index ("walls.2.thickness"). Throws ConfigError on an invalid value.
void ApplyOverrides(YAML::Node& root, const std::vector<ConfigOverride>& overrides);

/// A key a config does not have because another key states its value (one source per value).
struct MovedKey {
  std::string_view path;  ///< dotted key path that is refused, e.g. "nav.avoidance.robot_radius"
  std::string_view now;   ///< the key that holds the value, e.g. "sim.robot.radius"
};

/// Throws a located ConfigError, "<file>:<line>: <path>: unknown key; <why> <now>", for the
/// first key of `moved` present in `root` (from the file or from an override).
void RejectMovedKeys(const YAML::Node& root, const std::string& source,
                     const std::vector<ConfigOverride>& overrides,
                     const std::vector<MovedKey>& moved, std::string_view why);

namespace internal {

/// Where a value came from, for error messages.
struct ReadContext {
  std::string source;  ///< file name (or "<string>")
  std::string path;    ///< dotted key path of the current node
  const std::vector<ConfigOverride>* overrides = nullptr;

  ReadContext Child(std::string_view key) const {
    return {source, path.empty() ? std::string(key) : path + "." + std::string(key), overrides};
  }
  ReadContext Element(std::size_t i) const {
    return {source, path + "[" + std::to_string(i) + "]", overrides};
  }
};

/// Throws a located ConfigError: "<source>:<line>: <path>: <message>".
[[noreturn]] void Fail(const YAML::Node& node, const ReadContext& ctx, const std::string& message);
/// Rethrows a ConfigError from Validate() at `ctx`, locating e.key_path() inside `node`.
[[noreturn]] void FailValidation(const YAML::Node& node, const ReadContext& ctx,
                                 const core::ConfigError& e);
/// Rejects keys of `node` not in `valid`, suggesting the nearest valid key.
void CheckKeys(const YAML::Node& node, const ReadContext& ctx,
               const std::vector<std::string_view>& valid);

double ReadDouble(const YAML::Node& node, const ReadContext& ctx);
std::int64_t ReadInteger(const YAML::Node& node, const ReadContext& ctx, std::int64_t lo,
                         std::int64_t hi);
bool ReadBool(const YAML::Node& node, const ReadContext& ctx);
std::string ReadString(const YAML::Node& node, const ReadContext& ctx);
std::vector<double> ReadNumbers(const YAML::Node& node, const ReadContext& ctx,
                                std::size_t expected_size);

template <class T>
void Read(const YAML::Node& node, T& out, const ReadContext& ctx);

struct KeyCollector {
  std::vector<std::string_view>* keys;
  template <class T>
  void operator()(std::string_view key, T&) {
    keys->push_back(key);
  }
};

struct FieldReader {
  const YAML::Node* node;
  const ReadContext* ctx;
  template <class T>
  void operator()(std::string_view key, T& field) {
    const YAML::Node child = (*node)[std::string(key)];
    if (child) Read(child, field, ctx->Child(key));
  }
};

template <class T>
struct IsVector : std::false_type {};
template <class T, class A>
struct IsVector<std::vector<T, A>> : std::true_type {};
template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};
template <class T>
struct IsStringMap : std::false_type {};
template <class C, class A>
struct IsStringMap<std::map<std::string, std::string, C, A>> : std::true_type {};
template <class T>
struct IsDoubleArray : std::false_type {};
template <std::size_t N>
struct IsDoubleArray<std::array<double, N>> : std::true_type {};

/// Whether Read takes T from one YAML scalar: bool, integer, floating point, string or named
/// enum.
template <class T>
inline constexpr bool kIsScalarField =
    std::is_same_v<T, bool> || std::is_integral_v<T> || std::is_floating_point_v<T> ||
    std::is_same_v<T, std::string> || core::NamedEnum<T>;

/// Whether Read takes T from a fixed-size list of numbers: Vec2, Pose2 or std::array<double, N>.
template <class T>
inline constexpr bool kIsNumberTuple =
    std::is_same_v<T, core::Vec2> || std::is_same_v<T, core::Pose2> || IsDoubleArray<T>::value;

/// Reads a bool, integer (range-checked for T), floating point number, string or enum name.
template <class T>
void ReadScalar(const YAML::Node& node, T& out, const ReadContext& ctx) {
  if constexpr (std::is_same_v<T, bool>) {
    out = ReadBool(node, ctx);
  } else if constexpr (std::is_integral_v<T>) {
    out = static_cast<T>(ReadInteger(node, ctx, std::numeric_limits<T>::min(),
                                     static_cast<std::int64_t>(std::min<std::uint64_t>(
                                         std::numeric_limits<T>::max(), INT64_MAX))));
  } else if constexpr (std::is_floating_point_v<T>) {
    out = static_cast<T>(ReadDouble(node, ctx));
  } else if constexpr (std::is_same_v<T, std::string>) {
    out = ReadString(node, ctx);
  } else {
    const std::string name = ReadString(node, ctx);
    const auto value = core::ParseEnum<T>(name);
    if (!value) {
      Fail(node, ctx, "unknown value '" + name + "'; expected one of: " + core::EnumNameList<T>());
    }
    out = *value;
  }
}

/// Reads a Vec2 [x, y], a Pose2 [x, y, theta] or a std::array<double, N> of N numbers.
template <class T>
void ReadNumberTuple(const YAML::Node& node, T& out, const ReadContext& ctx) {
  if constexpr (std::is_same_v<T, core::Vec2>) {
    const auto v = ReadNumbers(node, ctx, 2);
    out = core::Vec2(v[0], v[1]);
  } else if constexpr (std::is_same_v<T, core::Pose2>) {
    const auto v = ReadNumbers(node, ctx, 3);
    out = core::Pose2(v[0], v[1], v[2]);
  } else {
    const auto v = ReadNumbers(node, ctx, out.size());
    std::copy(v.begin(), v.end(), out.begin());
  }
}

/// Reads a core::WordOr: one of its words alone, or else its value (a list naming a word among
/// other items is refused).
template <class T>
void ReadWordOr(const YAML::Node& node, T& out, const ReadContext& ctx) {
  using Word = typename decltype(out.word)::value_type;
  if (node.IsScalar()) {
    if (const auto word = core::ParseEnum<Word>(node.Scalar())) {
      out.word = word;
      out.value = {};
      return;
    }
  }
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      if (node[i].IsScalar() && core::ParseEnum<Word>(node[i].Scalar())) {
        Fail(node, ctx,
             "`" + node[i].Scalar() + "` stands alone: give either one of " +
                 core::EnumNameList<Word>() + " or a list, not both");
      }
    }
  }
  out.word.reset();
  Read(node, out.value, ctx);
}

/// Reads an optional (over its current value, if any) or a vector (replacing its elements).
template <class T>
void ReadContainer(const YAML::Node& node, T& out, const ReadContext& ctx) {
  if constexpr (IsOptional<T>::value) {
    typename T::value_type value{};
    if (out) value = *out;
    Read(node, value, ctx);
    out = std::move(value);
  } else {
    if (!node.IsSequence()) Fail(node, ctx, "expected a list");
    out.clear();
    out.resize(node.size());
    for (std::size_t i = 0; i < node.size(); ++i) Read(node[i], out[i], ctx.Element(i));
  }
}

/// Reads a mapping of names to scalars (each kept as its text: the reader of the map checks its
/// keys and values, e.g. a stack's options).
template <class T>
void ReadStringMap(const YAML::Node& node, T& out, const ReadContext& ctx) {
  if (node.IsNull()) {
    out.clear();
    return;
  }
  if (!node.IsMap()) Fail(node, ctx, "expected a mapping");
  out.clear();
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    out[key] = ReadString(item.second, ctx.Child(key));
  }
}

/// Reads a reflectable struct from a mapping: unknown keys refused, the fields given read, then
/// the struct validated (its errors located in the node).
template <class T>
void ReadStruct(const YAML::Node& node, T& out, const ReadContext& ctx) {
  if (!node.IsMap())
    Fail(node, ctx, node.IsNull() ? "expected a mapping, got nothing" : "expected a mapping");
  std::vector<std::string_view> keys;
  KeyCollector collector{&keys};
  out.Reflect(collector);
  CheckKeys(node, ctx, keys);
  FieldReader reader{&node, &ctx};
  out.Reflect(reader);
  if constexpr (core::Validatable<T>) {
    try {
      out.Validate();
    } catch (const core::ConfigError& e) {
      if (e.located()) throw;
      FailValidation(node, ctx, e);
    }
  }
}

/// Reads `out` from `node` strictly, by what kind of field T is.
template <class T>
void Read(const YAML::Node& node, T& out, const ReadContext& ctx) {
  if constexpr (kIsScalarField<T>) {
    ReadScalar(node, out, ctx);
  } else if constexpr (kIsNumberTuple<T>) {
    ReadNumberTuple(node, out, ctx);
  } else if constexpr (core::IsWordOr<T>::value) {
    ReadWordOr(node, out, ctx);
  } else if constexpr (IsOptional<T>::value || IsVector<T>::value) {
    ReadContainer(node, out, ctx);
  } else if constexpr (IsStringMap<T>::value) {
    ReadStringMap(node, out, ctx);
  } else if constexpr (core::Reflectable<T>) {
    ReadStruct(node, out, ctx);
  } else {
    static_assert(sizeof(T) == 0, "unsupported config field type");
  }
}

void Emit(YAML::Emitter& out, double v);
void Emit(YAML::Emitter& out, const std::string& v);
void Emit(YAML::Emitter& out, bool v);

template <class T>
void Write(YAML::Emitter& out, const T& value);

struct FieldWriter {
  YAML::Emitter* out;
  template <class T>
  void operator()(std::string_view key, const T& field) {
    if constexpr (IsOptional<T>::value) {
      if (!field) return;
    }
    *out << YAML::Key << std::string(key) << YAML::Value;
    Write(*out, field);
  }
};

template <class T>
void Write(YAML::Emitter& out, const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    out << value;
  } else if constexpr (std::is_integral_v<T>) {
    out << static_cast<long long>(value);
  } else if constexpr (std::is_floating_point_v<T>) {
    Emit(out, static_cast<double>(value));
  } else if constexpr (std::is_same_v<T, std::string>) {
    out << value;
  } else if constexpr (core::IsWordOr<T>::value) {
    if (value.word) {
      out << std::string(core::EnumName(*value.word));
    } else {
      Write(out, value.value);
    }
  } else if constexpr (core::NamedEnum<T>) {
    out << std::string(core::EnumName(value));
  } else if constexpr (std::is_same_v<T, core::Vec2>) {
    out << YAML::Flow << YAML::BeginSeq;
    Emit(out, value.x());
    Emit(out, value.y());
    out << YAML::EndSeq;
  } else if constexpr (std::is_same_v<T, core::Pose2>) {
    out << YAML::Flow << YAML::BeginSeq;
    Emit(out, value.x);
    Emit(out, value.y);
    Emit(out, value.theta);
    out << YAML::EndSeq;
  } else if constexpr (IsDoubleArray<T>::value) {
    out << YAML::Flow << YAML::BeginSeq;
    for (double v : value) Emit(out, v);
    out << YAML::EndSeq;
  } else if constexpr (IsOptional<T>::value) {
    Write(out, *value);
  } else if constexpr (IsVector<T>::value) {
    out << YAML::BeginSeq;
    for (const auto& v : value) Write(out, v);
    out << YAML::EndSeq;
  } else if constexpr (IsStringMap<T>::value) {
    out << YAML::BeginMap;
    for (const auto& [k, v] : value) out << YAML::Key << k << YAML::Value << v;
    out << YAML::EndMap;
  } else if constexpr (core::Reflectable<T>) {
    out << YAML::BeginMap;
    FieldWriter writer{&out};
    // Reflect() is non-const by convention; the writer only reads the fields.
    const_cast<T&>(value).Reflect(writer);
    out << YAML::EndMap;
  } else {
    static_assert(sizeof(T) == 0, "unsupported config field type");
  }
}

}  // namespace internal

/// Reads a config struct from a YAML node, strictly, then validates it. `source` names the
/// file in error messages. Keys missing from the node keep their default values.
template <core::Reflectable T>
T ReadConfig(const YAML::Node& node, const std::string& source,
             const std::vector<ConfigOverride>& overrides = {}) {
  T out{};
  internal::ReadContext ctx{source, "", &overrides};
  internal::Read(node, out, ctx);
  return out;
}

/// Loads, overrides and strictly reads a config file.
template <core::Reflectable T>
T LoadConfigFile(const std::filesystem::path& file,
                 const std::vector<ConfigOverride>& overrides = {}) {
  YAML::Node root = LoadYamlFile(file);
  ApplyOverrides(root, overrides);
  return ReadConfig<T>(root, file.string(), overrides);
}

/// The config as YAML text (the effective config written into manifests).
template <core::Reflectable T>
std::string ConfigToYaml(const T& config) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  internal::Write(out, config);
  return std::string(out.c_str()) + "\n";
}

}  // namespace retrace::io
