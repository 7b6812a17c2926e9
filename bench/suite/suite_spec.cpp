#include "bench/suite/suite_spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <optional>
#include <set>

#include "bench/metrics/flat_metrics.hpp"
#include "bench/suite/metric_pattern.hpp"
#include "core/config.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "io/config_yaml.hpp"
#include "io/read_file.hpp"

namespace retrace::bench {
namespace {

using io::internal::Fail;
using io::internal::ReadContext;

// Suite and entry names become file and metric names: no dots, no separators.
bool IsPlainName(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) != 0 || c == '_' || c == '-';
  });
}

YAML::Node Required(const YAML::Node& node, const ReadContext& ctx, const std::string& key) {
  const YAML::Node child = node[key];
  if (!child) Fail(node, ctx, "missing key '" + key + "'");
  return child;
}

std::string Digest(const std::filesystem::path& file) {
  const std::string text = io::ReadFileBytes(file);
  char hex[32];
  std::snprintf(hex, sizeof hex, "%016llx",
                static_cast<unsigned long long>(core::HashBytes(text.data(), text.size())));
  return std::string("fnv1a64:") + hex;
}

// An override's value as the YAML text `--set` would carry.
std::string YamlText(const YAML::Node& value) {
  YAML::Emitter out;
  out << YAML::Flow << value;
  return out.c_str();
}

// The scenario's own name, the default entry name.
std::string ScenarioName(const std::filesystem::path& scenario) {
  const YAML::Node root = io::LoadYamlFile(scenario);
  if (root.IsMap() && root["name"] && root["name"].IsScalar()) return root["name"].Scalar();
  return scenario.stem().string();
}

// The entry's `name`, or its scenario's when it has none; either must be able to name metrics.
std::string ReadEntryName(const YAML::Node& node, const ReadContext& ctx,
                          const std::filesystem::path& scenario) {
  if (const YAML::Node name = node["name"]) {
    std::string text = io::internal::ReadString(name, ctx.Child("name"));
    if (!IsPlainName(text)) {
      Fail(name, ctx.Child("name"),
           "'" + text + "' must be letters, digits, _ or - (it is part of metric names)");
    }
    return text;
  }
  std::string text = ScenarioName(scenario);
  if (!IsPlainName(text)) {
    Fail(node, ctx,
         "the scenario's name '" + text + "' cannot name metrics; give the entry a name");
  }
  return text;
}

// The entry's `set`: key.path: value pairs, as --set overrides.
std::vector<io::ConfigOverride> ReadEntrySet(const YAML::Node& set, const ReadContext& ctx) {
  if (!set.IsMap()) Fail(set, ctx, "expected a mapping of key.path: value");
  std::vector<io::ConfigOverride> overrides;
  for (const auto& kv : set) {
    const std::string key = kv.first.Scalar();
    if (key.empty()) Fail(kv.first, ctx, "empty key");
    overrides.push_back({key, YamlText(kv.second)});
  }
  return overrides;
}

SuiteEntry ReadEntry(const YAML::Node& node, const ReadContext& ctx,
                     const std::filesystem::path& dir) {
  if (!node.IsMap()) Fail(node, ctx, "expected a mapping with scenario, modes and seeds");
  io::internal::CheckKeys(node, ctx, {"scenario", "name", "modes", "seeds", "repeats", "set"});
  SuiteEntry entry;
  entry.line = node.Mark().line + 1;

  const YAML::Node scenario = Required(node, ctx, "scenario");
  entry.scenario_text = io::internal::ReadString(scenario, ctx.Child("scenario"));
  entry.scenario = (dir / entry.scenario_text).lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(entry.scenario, ec)) {
    Fail(scenario, ctx.Child("scenario"), "no scenario file " + entry.scenario.string());
  }

  entry.name = ReadEntryName(node, ctx, entry.scenario);

  const YAML::Node modes = Required(node, ctx, "modes");
  io::internal::Read(modes, entry.modes, ctx.Child("modes"));
  if (entry.modes.empty()) Fail(modes, ctx.Child("modes"), "needs at least one mode");
  for (std::size_t i = 0; i < entry.modes.size(); ++i) {
    if (std::count(entry.modes.begin(), entry.modes.end(), entry.modes[i]) > 1) {
      Fail(modes[i], ctx.Child("modes").Element(i),
           "mode '" + std::string(core::EnumName(entry.modes[i])) + "' is listed twice");
    }
  }

  const YAML::Node seeds = Required(node, ctx, "seeds");
  io::internal::Read(seeds, entry.seeds, ctx.Child("seeds"));
  if (entry.seeds.empty()) Fail(seeds, ctx.Child("seeds"), "needs at least one seed");
  for (std::size_t i = 0; i < entry.seeds.size(); ++i) {
    if (std::count(entry.seeds.begin(), entry.seeds.end(), entry.seeds[i]) > 1) {
      Fail(seeds[i], ctx.Child("seeds").Element(i),
           "seed " + std::to_string(entry.seeds[i]) + " is listed twice");
    }
  }

  if (const YAML::Node repeats = node["repeats"]) {
    entry.repeats =
        static_cast<int>(io::internal::ReadInteger(repeats, ctx.Child("repeats"), 1, 1000));
  }

  if (const YAML::Node set = node["set"]) entry.overrides = ReadEntrySet(set, ctx.Child("set"));
  return entry;
}

Tolerance ReadTolerance(const YAML::Node& node, const ReadContext& ctx) {
  if (!node.IsMap()) Fail(node, ctx, "expected a mapping of abs, rel, min, max, better or report");
  io::internal::CheckKeys(node, ctx, {"abs", "rel", "min", "max", "better", "report"});
  Tolerance t;
  auto non_negative = [&](const char* key, std::optional<double>& out) {
    if (const YAML::Node value = node[key]) {
      out = io::internal::ReadDouble(value, ctx.Child(key));
      if (*out < 0.0) Fail(value, ctx.Child(key), "must be >= 0, got " + core::FormatNumber(*out));
    }
  };
  non_negative("abs", t.abs);
  non_negative("rel", t.rel);
  if (const YAML::Node value = node["min"])
    t.min = io::internal::ReadDouble(value, ctx.Child("min"));
  if (const YAML::Node value = node["max"])
    t.max = io::internal::ReadDouble(value, ctx.Child("max"));
  if (t.min && t.max && *t.min > *t.max) Fail(node["max"], ctx.Child("max"), "must be >= min");
  if (const YAML::Node value = node["better"]) {
    Better better{};
    io::internal::Read(value, better, ctx.Child("better"));
    t.better = better;
  }
  if (const YAML::Node value = node["report"])
    t.report = io::internal::ReadBool(value, ctx.Child("report"));
  if (t.report && (t.has_delta() || t.has_bound() || t.better)) {
    Fail(node, ctx, "report: true stands alone (a reported metric is never gated)");
  }
  if (!t.report && !t.has_delta() && !t.has_bound()) {
    Fail(node, ctx, "needs abs, rel, min or max (or report: true)");
  }
  return t;
}

// True when the characters of `part` appear in `whole` in order ("tracking_rms" in
// "tracking_error_m.pooled.rms"): abbreviations of a name.
bool IsSubsequence(std::string_view part, std::string_view whole) {
  std::size_t i = 0;
  for (char c : whole) {
    if (i < part.size() && part[i] == c) ++i;
  }
  return i == part.size();
}

// The metric a pattern probably meant, for a "did you mean": the shortest name that holds the
// pattern's metric part (after "<entry>.<mode>.", wildcards dropped) as an abbreviation, else
// the nearest by edit distance.
std::string NearestMetric(const std::string& pattern) {
  std::size_t dot = pattern.find('.');
  if (dot != std::string::npos) dot = pattern.find('.', dot + 1);
  if (dot == std::string::npos) return "";
  std::string tail = pattern.substr(dot + 1);
  std::erase(tail, '*');
  std::string best;
  for (const std::string& name : AggregateMetricNames()) {
    if (IsSubsequence(tail, name) && (best.empty() || name.size() < best.size())) best = name;
  }
  if (!best.empty()) return best;
  std::size_t best_distance = SIZE_MAX;
  for (const std::string& name : AggregateMetricNames()) {
    const std::size_t d = core::EditDistance(tail, name);
    if (d < best_distance) {
      best_distance = d;
      best = name;
    }
  }
  return best;
}

// Each pattern must decide at least one metric: a pattern that matches nothing is a typo, one
// that later patterns override everywhere is dead.
void CheckRules(const SuiteSpec& spec, const YAML::Node& metrics, const ReadContext& ctx) {
  const std::vector<std::string> names = SuiteMetricNames(spec);
  std::vector<std::string> patterns;
  for (const MetricRule& rule : spec.rules) patterns.push_back(rule.pattern);
  std::vector<int> decides(patterns.size(), 0);
  std::vector<int> matches(patterns.size(), 0);
  for (const std::string& name : names) {
    const int decider = DecidingPattern(patterns, name);
    if (decider >= 0) ++decides[static_cast<std::size_t>(decider)];
    for (std::size_t i = 0; i < patterns.size(); ++i)
      matches[i] += MatchMetricPattern(patterns[i], name) ? 1 : 0;
  }
  std::size_t i = 0;
  for (const auto& kv : metrics) {
    const ReadContext rule_ctx = ctx.Child(patterns[i]);
    if (matches[i] == 0) {
      const std::string example = spec.entries.front().name + "." +
                                  std::string(core::EnumName(spec.entries.front().modes.front())) +
                                  ".success_rate";
      std::string message =
          "matches no metric (metrics are <entry>.<mode>.<name>, e.g. " + example + ")";
      const std::string nearest = NearestMetric(patterns[i]);
      if (!nearest.empty()) message += "; nearest metric name: '" + nearest + "'";
      Fail(kv.first, rule_ctx, message);
    }
    if (decides[i] == 0) {
      Fail(kv.first, rule_ctx,
           "a later pattern overrides it for every metric it matches (the last match decides: put "
           "general patterns first)");
    }
    ++i;
  }
}

}  // namespace

const std::vector<std::string>& AggregateMetricNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& [name, value] : FlatMetrics(AggregateMetrics{})) out.push_back(name);
    return out;
  }();
  return names;
}

std::vector<std::string> SuiteMetricNames(const SuiteSpec& spec) {
  std::vector<std::string> names;
  for (const SuiteEntry& entry : spec.entries) {
    for (MapMode mode : entry.modes) {
      const std::string prefix = entry.name + "." + std::string(core::EnumName(mode)) + ".";
      for (const std::string& metric : AggregateMetricNames()) names.push_back(prefix + metric);
    }
  }
  return names;
}

SuiteMetricName SplitSuiteMetricName(const std::string& name) {
  const std::size_t first = name.find('.');
  const std::size_t second = first == std::string::npos ? first : name.find('.', first + 1);
  if (second == std::string::npos) return {"", "", name};
  return {name.substr(0, first), name.substr(first + 1, second - first - 1),
          name.substr(second + 1)};
}

SuiteSpec SelectRuns(const SuiteSpec& spec, const std::vector<std::string>& selectors) {
  std::vector<std::set<MapMode>> chosen(spec.entries.size());
  for (const std::string& selector : selectors) {
    const std::size_t dot = selector.find('.');
    const std::string entry_name = selector.substr(0, dot);
    const auto entry = std::find_if(spec.entries.begin(), spec.entries.end(),
                                    [&](const SuiteEntry& e) { return e.name == entry_name; });
    if (entry == spec.entries.end()) {
      std::string names;
      for (const SuiteEntry& e : spec.entries) names += (names.empty() ? "" : ", ") + e.name;
      throw core::ConfigError("",
                              "--only " + selector + ": suite '" + spec.name + "' has no entry '" +
                                  entry_name + "' (entries: " + names + ")",
                              true);
    }
    std::set<MapMode>& modes = chosen[static_cast<std::size_t>(entry - spec.entries.begin())];
    if (dot == std::string::npos) {
      modes.insert(entry->modes.begin(), entry->modes.end());
      continue;
    }
    const std::string mode_name = selector.substr(dot + 1);
    const std::optional<MapMode> mode = core::ParseEnum<MapMode>(mode_name);
    if (!mode || std::find(entry->modes.begin(), entry->modes.end(), *mode) == entry->modes.end()) {
      std::string names;
      for (MapMode m : entry->modes)
        names += (names.empty() ? "" : ", ") + std::string(core::EnumName(m));
      throw core::ConfigError("",
                              "--only " + selector + ": entry '" + entry->name +
                                  "' does not run mode '" + mode_name + "' (its modes: " + names +
                                  ")",
                              true);
    }
    modes.insert(*mode);
  }
  SuiteSpec selected = spec;
  selected.entries.clear();
  for (std::size_t e = 0; e < spec.entries.size(); ++e) {
    if (chosen[e].empty()) continue;
    SuiteEntry entry = spec.entries[e];
    std::erase_if(entry.modes, [&](MapMode m) { return !chosen[e].contains(m); });
    selected.entries.push_back(std::move(entry));
  }
  return selected;
}

SuiteSpec LoadSuiteSpec(const std::filesystem::path& file) {
  const YAML::Node root = io::LoadYamlFile(file);
  const ReadContext ctx{file.string(), "", nullptr};
  if (!root.IsMap()) Fail(root, ctx, "expected a mapping with name, entries and metrics");
  io::internal::CheckKeys(root, ctx, {"name", "entries", "metrics"});

  SuiteSpec spec;
  spec.source = file;
  spec.digest = Digest(file);
  const YAML::Node name = Required(root, ctx, "name");
  spec.name = io::internal::ReadString(name, ctx.Child("name"));
  if (!IsPlainName(spec.name)) {
    Fail(name, ctx.Child("name"),
         "'" + spec.name + "' must be letters, digits, _ or - (it names the baseline file)");
  }

  const YAML::Node entries = Required(root, ctx, "entries");
  if (!entries.IsSequence() || entries.size() == 0)
    Fail(entries, ctx.Child("entries"), "expected a list of entries");
  std::set<std::string> entry_names;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const ReadContext entry_ctx = ctx.Child("entries").Element(i);
    spec.entries.push_back(ReadEntry(entries[i], entry_ctx, file.parent_path()));
    if (!entry_names.insert(spec.entries.back().name).second) {
      Fail(entries[i], entry_ctx,
           "entry name '" + spec.entries.back().name + "' is used twice; give one a name");
    }
  }

  const YAML::Node metrics = Required(root, ctx, "metrics");
  const ReadContext metrics_ctx = ctx.Child("metrics");
  if (!metrics.IsMap() || metrics.size() == 0)
    Fail(metrics, metrics_ctx, "expected a mapping of pattern: tolerance");
  for (const auto& kv : metrics) {
    MetricRule rule;
    rule.pattern = kv.first.Scalar();
    rule.line = kv.first.Mark().line + 1;
    const ReadContext rule_ctx = metrics_ctx.Child(rule.pattern);
    if (const std::string problem = PatternProblem(rule.pattern); !problem.empty())
      Fail(kv.first, rule_ctx, problem);
    rule.tolerance = ReadTolerance(kv.second, rule_ctx);
    spec.rules.push_back(std::move(rule));
  }
  CheckRules(spec, metrics, metrics_ctx);
  return spec;
}

}  // namespace retrace::bench
