#include "io/config_yaml.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "io/read_file.hpp"

namespace retrace::io {
namespace internal {
namespace {

// The --set override that produced a key path, if any.
const ConfigOverride* OverrideFor(const ReadContext& ctx, const std::string& path) {
  if (ctx.overrides == nullptr) return nullptr;
  for (const auto& o : *ctx.overrides) {
    // Overrides use '.' for list indices too; compare with brackets folded to dots.
    std::string p = path;
    for (char& c : p) {
      if (c == '[') c = '.';
    }
    std::erase(p, ']');
    if (p == o.key_path || p.rfind(o.key_path + ".", 0) == 0) {
      return &o;
    }
  }
  return nullptr;
}

std::string Location(const YAML::Node& node, const ReadContext& ctx, const std::string& path) {
  // An overridden value's marks point into the --set text, not into the file.
  if (const ConfigOverride* o = OverrideFor(ctx, path)) {
    return ctx.source + " (--set " + o->key_path + "=" + o->value + ")";
  }
  const YAML::Mark mark = node.Mark();
  if (!mark.is_null() && mark.line >= 0) {
    return ctx.source + ":" + std::to_string(mark.line + 1);
  }
  return ctx.source;
}

std::string Describe(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a mapping";
  return "nothing";
}

}  // namespace

void Fail(const YAML::Node& node, const ReadContext& ctx, const std::string& message) {
  const std::string where = Location(node, ctx, ctx.path);
  const std::string key = ctx.path.empty() ? "" : ctx.path + ": ";
  throw core::ConfigError(ctx.path, where + ": " + key + message, /*located=*/true);
}

void FailValidation(const YAML::Node& node, const ReadContext& ctx, const core::ConfigError& e) {
  // Walk the dotted key relative to this struct to find the line of the offending value.
  YAML::Node at = node;
  ReadContext where = ctx;
  std::stringstream keys(e.key_path());
  std::string key;
  while (!e.key_path().empty() && std::getline(keys, key, '.')) {
    where = where.Child(key);
    if (at.IsMap() && at[key]) {
      at = at[key];
    }
  }
  Fail(at, where, e.detail());
}

void CheckKeys(const YAML::Node& node, const ReadContext& ctx,
               const std::vector<std::string_view>& valid) {
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    if (std::find(valid.begin(), valid.end(), key) != valid.end()) continue;
    std::string_view nearest;
    std::size_t best = SIZE_MAX;
    for (std::string_view v : valid) {
      const std::size_t d = core::EditDistance(key, v);
      if (d < best) {
        best = d;
        nearest = v;
      }
    }
    std::string message = "unknown key";
    if (!nearest.empty()) message += "; did you mean '" + std::string(nearest) + "'?";
    Fail(kv.first, ctx.Child(key), message);
  }
}

double ReadDouble(const YAML::Node& node, const ReadContext& ctx) {
  if (!node.IsScalar()) Fail(node, ctx, "expected a number, got " + Describe(node));
  double v = 0.0;
  if (!YAML::convert<double>::decode(node, v)) {
    Fail(node, ctx, "expected a number, got " + Describe(node));
  }
  if (!std::isfinite(v)) Fail(node, ctx, "must be a finite number, got " + Describe(node));
  return v;
}

std::int64_t ReadInteger(const YAML::Node& node, const ReadContext& ctx, std::int64_t lo,
                         std::int64_t hi) {
  if (!node.IsScalar()) Fail(node, ctx, "expected an integer, got " + Describe(node));
  const std::string& s = node.Scalar();
  std::int64_t v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size()) {
    Fail(node, ctx, "expected an integer, got " + Describe(node));
  }
  if (v < lo || v > hi) {
    Fail(node, ctx,
         "integer " + s + " out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return v;
}

bool ReadBool(const YAML::Node& node, const ReadContext& ctx) {
  bool v = false;
  if (!node.IsScalar() || !YAML::convert<bool>::decode(node, v)) {
    Fail(node, ctx, "expected true or false, got " + Describe(node));
  }
  return v;
}

std::string ReadString(const YAML::Node& node, const ReadContext& ctx) {
  if (!node.IsScalar()) Fail(node, ctx, "expected a string, got " + Describe(node));
  return node.Scalar();
}

std::vector<double> ReadNumbers(const YAML::Node& node, const ReadContext& ctx,
                                std::size_t expected_size) {
  if (!node.IsSequence() || node.size() != expected_size) {
    Fail(node, ctx,
         "expected a list of " + std::to_string(expected_size) + " numbers, got " +
             (node.IsSequence() ? "a list of " + std::to_string(node.size()) : Describe(node)));
  }
  std::vector<double> out(expected_size);
  for (std::size_t i = 0; i < expected_size; ++i) out[i] = ReadDouble(node[i], ctx.Element(i));
  return out;
}

void Emit(YAML::Emitter& out, double v) {
  std::string s = core::FormatNumber(v);
  // Keep it a float in YAML's eyes so that round trips do not change the type.
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  out << s;
}
void Emit(YAML::Emitter& out, const std::string& v) { out << v; }
void Emit(YAML::Emitter& out, bool v) { out << v; }

}  // namespace internal

ConfigOverride ParseOverride(std::string_view text) {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0) {
    throw core::ConfigError("", "--set expects key.path=value, got '" + std::string(text) + "'");
  }
  return {std::string(text.substr(0, eq)), std::string(text.substr(eq + 1))};
}

YAML::Node LoadYamlFile(const std::filesystem::path& file) {
  const std::string text = ReadFileBytes(file);
  try {
    YAML::Node root = YAML::Load(text);
    if (!root || root.IsNull()) {
      throw core::ConfigError("", file.string() + ": file is empty", /*located=*/true);
    }
    return root;
  } catch (const YAML::ParserException& e) {
    throw core::ConfigError(
        "", file.string() + ":" + std::to_string(e.mark.line + 1) + ": invalid YAML: " + e.msg,
        /*located=*/true);
  }
}

namespace {

bool IsIndex(const std::string& s) {
  return !s.empty() &&
         std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

[[noreturn]] void OverrideFail(const ConfigOverride& o, const std::string& message) {
  throw core::ConfigError(o.key_path, "--set " + o.key_path + "=" + o.value + ": " + message,
                          /*located=*/true);
}

void ApplyOverride(YAML::Node& root, const ConfigOverride& o) {
  YAML::Node value;
  try {
    value = YAML::Load(o.value);
  } catch (const YAML::ParserException& e) {
    OverrideFail(o, "invalid YAML value: " + e.msg);
  }
  std::vector<std::string> keys;
  std::stringstream ss(o.key_path);
  std::string key;
  while (std::getline(ss, key, '.')) {
    if (key.empty()) OverrideFail(o, "empty key in path");
    keys.push_back(key);
  }
  if (keys.empty()) OverrideFail(o, "empty key path");
  // yaml-cpp nodes are handles: walk with copies and assign through the last one.
  YAML::Node cur = root;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const bool last = i + 1 == keys.size();
    if (cur.IsSequence()) {
      if (!IsIndex(keys[i])) OverrideFail(o, "'" + keys[i] + "' addresses a list: use an index");
      // Digits only (IsIndex); more of them than any list holds are out of range, not an error
      // of the number conversion.
      std::size_t k = 0;
      const auto [end, ec] = std::from_chars(keys[i].data(), keys[i].data() + keys[i].size(), k);
      if (ec != std::errc() || end != keys[i].data() + keys[i].size() || k >= cur.size()) {
        OverrideFail(o, "list index " + keys[i] + " out of range (the list has " +
                            std::to_string(cur.size()) + " elements)");
      }
      if (last) {
        cur[k] = value;
      } else {
        YAML::Node next = cur[k];
        cur.reset(next);
      }
    } else {
      if (cur.IsScalar()) OverrideFail(o, "'" + keys[i] + "' is inside a scalar value");
      if (last) {
        cur[keys[i]] = value;
      } else {
        if (!cur[keys[i]]) cur[keys[i]] = YAML::Node(YAML::NodeType::Map);
        YAML::Node next = cur[keys[i]];
        cur.reset(next);
      }
    }
  }
}

}  // namespace

void ApplyOverrides(YAML::Node& root, const std::vector<ConfigOverride>& overrides) {
  for (const auto& o : overrides) {
    try {
      ApplyOverride(root, o);
    } catch (const YAML::Exception& e) {
      OverrideFail(o, "cannot set this key: " + e.msg);
    }
  }
}

void RejectMovedKeys(const YAML::Node& root, const std::string& source,
                     const std::vector<ConfigOverride>& overrides,
                     const std::vector<MovedKey>& moved, std::string_view why) {
  for (const MovedKey& m : moved) {
    internal::ReadContext ctx{source, "", &overrides};
    // YAML::Node's operator= writes into the node it refers to: walk with reset() instead.
    YAML::Node at;
    at.reset(root);
    YAML::Node key_node;
    std::stringstream keys{std::string(m.path)};
    std::string key;
    bool present = true;
    while (present && std::getline(keys, key, '.')) {
      present = false;
      if (!at.IsMap()) break;
      for (const auto& kv : at) {
        if (kv.first.Scalar() != key) continue;
        key_node.reset(kv.first);
        at.reset(kv.second);
        ctx = ctx.Child(key);
        present = true;
        break;
      }
    }
    if (present) {
      internal::Fail(key_node, ctx, "unknown key; " + std::string(why) + " " + std::string(m.now));
    }
  }
}

}  // namespace retrace::io
