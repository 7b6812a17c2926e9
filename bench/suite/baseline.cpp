#include "bench/suite/baseline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bench/metrics/flat_metrics.hpp"
#include "core/errors.hpp"
#include "io/json_writer.hpp"

namespace retrace::bench {
namespace {

constexpr const char* kFormat = "retrace-baseline/1";

[[noreturn]] void NotABaseline(const std::filesystem::path& file, const std::string& what) {
  throw core::IoError(file.string() + ": not a retrace baseline: " + what);
}

std::string StringField(const nlohmann::json& root, const char* key,
                        const std::filesystem::path& file) {
  if (!root.contains(key) || !root[key].is_string())
    NotABaseline(file, std::string("'") + key + "' must be a string");
  return root[key].get<std::string>();
}

std::map<std::string, double> NumberMap(const nlohmann::json& root, const char* key,
                                        const std::filesystem::path& file) {
  if (!root.contains(key) || !root[key].is_object())
    NotABaseline(file, std::string("'") + key + "' must be an object");
  std::map<std::string, double> out;
  for (const auto& [name, value] : root[key].items()) {
    if (value.is_null()) {
      out[name] = std::numeric_limits<double>::quiet_NaN();
    } else if (value.is_number()) {
      out[name] = value.get<double>();
    } else {
      NotABaseline(file, std::string(key) + "." + name + " must be a number or null");
    }
  }
  return out;
}

// The first field where two entry definitions differ, for the error message.
std::string FirstDifference(const nlohmann::json& recorded, const nlohmann::json& now) {
  for (const auto& [key, value] : now.items()) {
    if (!recorded.contains(key) || recorded[key] != value) {
      return key + " " + (recorded.contains(key) ? recorded[key].dump() : std::string("(none)")) +
             " -> " + value.dump();
    }
  }
  return "fields differ";
}

}  // namespace

std::optional<double> Baseline::Find(const std::string& name) const {
  if (const auto it = metrics.find(name); it != metrics.end()) return it->second;
  if (const auto it = timing.find(name); it != timing.end()) return it->second;
  return std::nullopt;
}

nlohmann::json EntryDefinition(const SuiteEntry& entry) {
  nlohmann::json modes = nlohmann::json::array();
  for (MapMode mode : entry.modes) modes.push_back(std::string(core::EnumName(mode)));
  nlohmann::json set = nlohmann::json::object();
  for (const io::ConfigOverride& o : entry.overrides) set[o.key_path] = o.value;
  return {{"name", entry.name},   {"scenario", entry.scenario_text}, {"modes", modes},
          {"seeds", entry.seeds}, {"repeats", entry.repeats},        {"set", set}};
}

Baseline MakeBaseline(const SuiteSpec& spec, const SuiteResults& results) {
  Baseline b;
  b.suite = spec.name;
  b.suite_file = spec.source.string();
  b.suite_digest = spec.digest;
  b.git_revision = BuildRevision();
  b.build_type = BuildType();
  b.date = UtcNow();
  for (const SuiteEntry& entry : spec.entries) b.entries.push_back(EntryDefinition(entry));
  for (const auto& [name, metric] : results.metrics) {
    const std::string flat = name.substr(name.find('.', name.find('.') + 1) + 1);
    (IsTimingMetric(flat) ? b.timing : b.metrics)[name] = metric.mean;
  }
  return b;
}

Baseline ReadBaseline(const std::filesystem::path& file) {
  const nlohmann::json root = io::ReadJsonFile(file);
  if (!root.is_object()) NotABaseline(file, "expected a JSON object");
  if (!root.contains("format") || root["format"] != kFormat) {
    NotABaseline(file, std::string("'format' must be \"") + kFormat + "\"");
  }
  Baseline b;
  b.suite = StringField(root, "suite", file);
  b.suite_file = StringField(root, "suite_file", file);
  b.suite_digest = StringField(root, "suite_digest", file);
  b.git_revision = StringField(root, "git_revision", file);
  b.build_type = StringField(root, "build_type", file);
  b.date = StringField(root, "date", file);
  if (!root.contains("entries") || !root["entries"].is_array())
    NotABaseline(file, "'entries' must be a list");
  for (const nlohmann::json& entry : root["entries"]) {
    if (!entry.is_object() || !entry.contains("name") || !entry["name"].is_string()) {
      NotABaseline(file, "every entry needs a name");
    }
  }
  b.entries = root["entries"];
  b.metrics = NumberMap(root, "metrics", file);
  b.timing = NumberMap(root, "timing", file);
  return b;
}

void WriteBaseline(const std::filesystem::path& file, const Baseline& b) {
  // nlohmann::ordered_json keeps the header fields first, where a reader looks.
  nlohmann::ordered_json root;
  root["format"] = kFormat;
  root["suite"] = b.suite;
  root["suite_file"] = b.suite_file;
  root["suite_digest"] = b.suite_digest;
  Provenance provenance;
  provenance.git_revision = b.git_revision;
  provenance.build_type = b.build_type;
  provenance.date = b.date;
  WriteProvenance(provenance, &root);
  root["entries"] = b.entries;
  nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
  for (const auto& [name, value] : b.metrics) metrics[name] = io::JsonNumber(value);
  nlohmann::ordered_json timing = nlohmann::ordered_json::object();
  for (const auto& [name, value] : b.timing) timing[name] = io::JsonNumber(value);
  root["metrics"] = metrics;
  root["timing"] = timing;
  io::WriteJsonAtomic(file, root);
}

void CheckBaselineMatches(const Baseline& baseline, const SuiteSpec& spec,
                          const std::filesystem::path& file) {
  const std::string update =
      "; record a new one with `retrace bench " + spec.source.string() + " --update-baseline`";
  if (baseline.suite != spec.name) {
    throw core::ConfigError("",
                            file.string() + " is the baseline of suite '" + baseline.suite +
                                "', not of '" + spec.name + "' (" + spec.source.string() + ")",
                            true);
  }
  for (const SuiteEntry& entry : spec.entries) {
    const nlohmann::json now = EntryDefinition(entry);
    const nlohmann::json* recorded = nullptr;
    for (const nlohmann::json& e : baseline.entries) {
      if (e["name"] == entry.name) recorded = &e;
    }
    if (recorded == nullptr) {
      throw core::ConfigError(
          "", file.string() + ": entry '" + entry.name + "' is not in the baseline" + update, true);
    }
    if (*recorded != now) {
      throw core::ConfigError("",
                              file.string() + ": entry '" + entry.name +
                                  "' has changed since the baseline (" +
                                  FirstDifference(*recorded, now) + ")" + update,
                              true);
    }
  }
  if (baseline.entries.size() != spec.entries.size()) {
    for (const nlohmann::json& e : baseline.entries) {
      const std::string name = e["name"].get<std::string>();
      const bool present = std::any_of(spec.entries.begin(), spec.entries.end(),
                                       [&](const SuiteEntry& entry) { return entry.name == name; });
      if (!present) {
        throw core::ConfigError("",
                                file.string() + ": entry '" + name +
                                    "' of the baseline is no longer in the suite" + update,
                                true);
      }
    }
  }
}

}  // namespace retrace::bench
