#include "bench/sweep/sweep_spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>

#include "bench/metrics/flat_metrics.hpp"
#include "core/config.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "io/config_yaml.hpp"

namespace retrace::bench {
namespace {

using io::internal::Fail;
using io::internal::ReadContext;

// At most this many cases (combinations times repeats): about a week of episodes on two
// cores. A million, the limit before, let a 6-key grid expand into 2 GB of strings (found by
// fuzz_sweep, 2026-11-26) before a single case ran.
constexpr std::size_t kMaxCases = 100'000;
constexpr std::int64_t kMaxSamples = 100'000;
constexpr std::int64_t kMaxInt = 1'000'000'000'000;  // int_uniform bounds: no overflow anywhere

int LineOf(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() || mark.line < 0 ? 0 : mark.line + 1;
}

// A value as the YAML text that an override carries: scalars verbatim, lists and maps in flow
// style on one line (so that they fit a CSV cell and read back as the same YAML).
std::string ValueText(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter out;
  out.SetSeqFormat(YAML::Flow);
  out.SetMapFormat(YAML::Flow);
  out << node;
  return out.c_str();
}

bool IsPrefixKey(const std::string& prefix, const std::string& key) {
  return key.size() > prefix.size() && key.compare(0, prefix.size(), prefix) == 0 &&
         key[prefix.size()] == '.';
}

// One varied key while it is being read: its column values come later from the expansion.
struct Varied {
  std::string key;
  SweepKeySource source;
  YAML::Node key_node;
};

class SpecReader {
 public:
  explicit SpecReader(const std::filesystem::path& file) : ctx_{file.string(), "", nullptr} {}

  const ReadContext& ctx() const { return ctx_; }

  // Rejects malformed key paths, the keys a sweep sets itself, and keys given twice.
  void CheckVariedKey(const YAML::Node& key_node, const ReadContext& at, const std::string& key,
                      const std::string& section) {
    CheckKeyPath(key_node, at, key);
    if (key == "playback.repeats" || key == "playback" || IsPrefixKey("playback.repeats", key)) {
      Fail(key_node, at,
           "a sweep runs one playback per case; replicate with the sweep's `repeats`");
    }
    if (key == "modes" || IsPrefixKey("modes", key)) {
      Fail(key_node, at, "each case runs one map mode; vary `mode` instead");
    }
    for (const Varied& v : varied_) {
      if (v.key == key) {
        Fail(key_node, at,
             "is already varied in " + v.source.section + " (line " +
                 std::to_string(v.source.line) + ")");
      }
      if (IsPrefixKey(v.key, key) || IsPrefixKey(key, v.key)) {
        Fail(key_node, at,
             "overlaps with '" + v.key + "', varied in " + v.source.section + " (line " +
                 std::to_string(v.source.line) + ")");
      }
    }
    varied_.push_back({key, {section, LineOf(key_node)}, key_node});
  }

  void CheckKeyPath(const YAML::Node& key_node, const ReadContext& at, const std::string& key) {
    if (key.empty() || key.front() == '.' || key.back() == '.' ||
        key.find("..") != std::string::npos) {
      Fail(key_node, at, "not a key path (write it like nav.localizer.particles)");
    }
  }

  void CheckModeValue(const YAML::Node& value, const ReadContext& at) {
    const std::string text = ValueText(value);
    if (!value.IsScalar() || !core::ParseEnum<MapMode>(text)) {
      Fail(value, at,
           "unknown map mode '" + text + "'; expected one of: " + core::EnumNameList<MapMode>());
    }
  }

  // The values of one grid or zip key: a non-empty list.
  std::vector<std::string> ReadList(const YAML::Node& value, const ReadContext& at,
                                    const std::string& key) {
    if (!value.IsSequence() || value.size() == 0) {
      Fail(
          value, at,
          value.IsSequence() ? "empty list: give at least one value" : "expected a list of values");
    }
    std::vector<std::string> out;
    for (std::size_t i = 0; i < value.size(); ++i) {
      if (key == "mode") CheckModeValue(value[i], at.Element(i));
      out.push_back(ValueText(value[i]));
    }
    return out;
  }

  const std::vector<Varied>& varied() const { return varied_; }

 private:
  ReadContext ctx_;
  std::vector<Varied> varied_;
};

void Flatten(const YAML::Node& node, const std::string& prefix,
             std::vector<std::pair<std::string, YAML::Node>>& out,
             std::vector<YAML::Node>& key_nodes, const YAML::Node& key_node) {
  if (node.IsMap() && node.size() > 0 && !prefix.empty()) {
    for (const auto& kv : node)
      Flatten(kv.second, prefix + "." + kv.first.Scalar(), out, key_nodes, kv.first);
    return;
  }
  out.emplace_back(prefix, node);
  key_nodes.push_back(key_node);
}

// One random parameter's distribution.
struct Distribution {
  enum class Kind { kUniform, kLogUniform, kIntUniform, kChoice } kind = Kind::kUniform;
  double lo = 0.0, hi = 0.0;
  std::int64_t int_lo = 0, int_hi = 0;
  std::vector<std::string> choices;

  std::string Draw(core::Rng& rng) const {
    switch (kind) {
      case Kind::kUniform: {
        // lo + (hi - lo) u can round up to hi; keep the documented half-open range.
        const double v = rng.Uniform(lo, hi);
        return core::FormatNumber(v < hi ? v : std::nextafter(hi, lo));
      }
      case Kind::kLogUniform: {
        const double v = std::exp(rng.Uniform(std::log(lo), std::log(hi)));
        return core::FormatNumber(std::clamp(v < hi ? v : std::nextafter(hi, lo), lo, hi));
      }
      case Kind::kIntUniform: {
        const auto span = static_cast<std::uint64_t>(int_hi - int_lo) + 1;
        return std::to_string(int_lo + static_cast<std::int64_t>(rng.UniformIndex(span)));
      }
      case Kind::kChoice:
        return choices[rng.UniformIndex(choices.size())];
    }
    return {};
  }
};

Distribution ReadDistribution(SpecReader& reader, const YAML::Node& node, const ReadContext& at,
                              const std::string& key) {
  static const std::vector<std::string_view> kKinds = {"uniform", "log_uniform", "int_uniform",
                                                       "choice"};
  if (!node.IsMap() || node.size() != 1) {
    Fail(node, at,
         "expected one distribution: {uniform: [lo, hi]}, {log_uniform: [lo, hi]}, "
         "{int_uniform: [lo, hi]} or {choice: [values]}");
  }
  io::internal::CheckKeys(node, at, kKinds);
  const auto kv = *node.begin();
  const std::string kind = kv.first.Scalar();
  const ReadContext here = at.Child(kind);
  Distribution d;
  if (kind == "choice") {
    d.kind = Distribution::Kind::kChoice;
    d.choices = reader.ReadList(kv.second, here, key);
    return d;
  }
  if (key == "mode") Fail(kv.first, here, "a map mode is drawn with {choice: [...]}");
  if (kind == "int_uniform") {
    if (!kv.second.IsSequence() || kv.second.size() != 2)
      Fail(kv.second, here, "expected [lo, hi]");
    d.kind = Distribution::Kind::kIntUniform;
    d.int_lo = io::internal::ReadInteger(kv.second[0], here.Element(0), -kMaxInt, kMaxInt);
    d.int_hi = io::internal::ReadInteger(kv.second[1], here.Element(1), -kMaxInt, kMaxInt);
    if (d.int_hi < d.int_lo) Fail(kv.second, here, "needs lo <= hi");
    return d;
  }
  const std::vector<double> range = io::internal::ReadNumbers(kv.second, here, 2);
  d.lo = range[0];
  d.hi = range[1];
  if (!(d.lo < d.hi)) Fail(kv.second, here, "needs lo < hi");
  if (kind == "log_uniform") {
    d.kind = Distribution::Kind::kLogUniform;
    if (!(d.lo > 0.0)) Fail(kv.second, here, "needs 0 < lo < hi");
  }
  return d;
}

std::vector<std::string> ReadMetrics(const YAML::Node& node, const ReadContext& at) {
  if (!node.IsSequence() || node.size() == 0)
    Fail(node, at, "expected a non-empty list of metric names");
  const std::vector<std::string>& known = KnownSweepMetrics();
  std::vector<std::string> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string name = io::internal::ReadString(node[i], at.Element(i));
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      // Metric names are long dotted paths that people abbreviate ("tracking_rms"): rank by the
      // edit distance without the letters left out, then by the plain edit distance.
      std::string nearest;
      std::pair<std::size_t, std::size_t> best{SIZE_MAX, SIZE_MAX};
      for (const std::string& k : known) {
        const std::size_t d = core::EditDistance(name, k);
        const std::size_t left_out = k.size() > name.size() ? k.size() - name.size() : 0;
        const std::pair<std::size_t, std::size_t> score{d - std::min(d, left_out), d};
        if (score < best) best = score, nearest = k;
      }
      Fail(node[i], at.Element(i),
           "unknown metric '" + name + "'; did you mean '" + nearest + "'?");
    }
    if (std::find(out.begin(), out.end(), name) != out.end())
      Fail(node[i], at.Element(i), "'" + name + "' is listed twice");
    // Repeatability compares several playback runs of one teaching drive; a case has one run,
    // so the metric would be nan in every row.
    if (name.rfind("repeatability_", 0) == 0) {
      Fail(node[i], at.Element(i),
           "'" + name + "' needs several playback runs of one teaching drive, and each case of " +
               "a sweep has one; use `retrace run --repeats N` for it");
    }
    out.push_back(name);
  }
  return out;
}

// Multiplies counts of combinations, refusing sweeps too big to run (and overflow).
std::size_t CheckedProduct(std::size_t a, std::size_t b, const YAML::Node& node,
                           const ReadContext& at) {
  if (b != 0 && a > kMaxCases / b) {
    Fail(node, at,
         "the sweep has more than " + std::to_string(kMaxCases) +
             " cases; split it into several sweeps");
  }
  return a * b;
}

// name, scenario, mode and repeats. The name (default: the file's stem) must be able to name a
// results folder.
void ReadSweepBasics(const YAML::Node& root, SpecReader& reader, SweepSpec* spec) {
  const ReadContext& ctx = reader.ctx();
  const std::filesystem::path& file = spec->file;
  spec->name = root["name"] ? io::internal::ReadString(root["name"], ctx.Child("name"))
                            : file.stem().string();
  const std::string& name = spec->name;
  const bool safe_name = !name.empty() && name != "." && name != ".." &&
                         std::all_of(name.begin(), name.end(), [](unsigned char c) {
                           return std::isalnum(c) != 0 || c == '_' || c == '-' || c == '.';
                         });
  if (!safe_name) {
    Fail(root["name"] ? root["name"] : root, ctx.Child("name"),
         "'" + name + "' cannot name a results folder: use letters, digits, '_', '-' and '.'");
  }
  if (!root["scenario"]) Fail(root, ctx.Child("scenario"), "missing: name the base scenario file");
  spec->scenario =
      file.parent_path() / io::internal::ReadString(root["scenario"], ctx.Child("scenario"));
  if (root["mode"]) {
    reader.CheckModeValue(root["mode"], ctx.Child("mode"));
    spec->mode = *core::ParseEnum<MapMode>(root["mode"].Scalar());
  }
  if (root["repeats"]) {
    spec->repeats = static_cast<int>(
        io::internal::ReadInteger(root["repeats"], ctx.Child("repeats"), 1, 10000));
  }
}

// Fixed overrides: `set` (flattened to key paths), then --set.
void ReadFixedOverrides(const YAML::Node& root, SpecReader& reader,
                        const std::vector<io::ConfigOverride>& cli_overrides, SweepSpec* spec) {
  const ReadContext& ctx = reader.ctx();
  if (const YAML::Node set = root["set"]) {
    if (!set.IsMap()) Fail(set, ctx.Child("set"), "expected a mapping of key paths to values");
    std::vector<std::pair<std::string, YAML::Node>> flat;
    std::vector<YAML::Node> key_nodes;
    for (const auto& kv : set) Flatten(kv.second, kv.first.Scalar(), flat, key_nodes, kv.first);
    for (std::size_t i = 0; i < flat.size(); ++i) {
      reader.CheckKeyPath(key_nodes[i], ctx.Child("set").Child(flat[i].first), flat[i].first);
      spec->fixed.push_back({flat[i].first, ValueText(flat[i].second)});
      spec->fixed_sources.push_back({"set", LineOf(key_nodes[i])});
    }
  }
  for (const io::ConfigOverride& o : cli_overrides) {
    spec->fixed.push_back(o);
    spec->fixed_sources.push_back({"--set", 0});
  }
}

// A fixed key must be a scenario key the sweep does not set itself (mode, playback.repeats).
void RequireFixedKeysOfScenario(const SweepSpec& spec, const ReadContext& ctx) {
  for (std::size_t i = 0; i < spec.fixed.size(); ++i) {
    const std::string& key = spec.fixed[i].key_path;
    const std::string where = spec.fixed_sources[i].line > 0
                                  ? ctx.source + ":" + std::to_string(spec.fixed_sources[i].line)
                                  : ctx.source + " (--set " + key + "=" + spec.fixed[i].value + ")";
    if (key == "mode")
      throw core::ConfigError(key, where + ": mode: not a scenario key; use the sweep's `mode`",
                              true);
    if (key == "playback.repeats" || key == "modes" || IsPrefixKey("modes", key)) {
      throw core::ConfigError(
          key,
          where + ": " + key + ": set by the sweep itself (one playback of one `mode` per case)",
          true);
    }
  }
}

// The rows of one varied section: [row][key].
using SectionRows = std::vector<std::vector<std::string>>;

// `grid`: every combination of its keys' values, the first key varying slowest.
SectionRows ReadGridSection(const YAML::Node& grid, const ReadContext& at, SpecReader& reader,
                            std::vector<std::string>* parameters) {
  if (!grid.IsMap() || grid.size() == 0)
    Fail(grid, at, "expected a mapping of key paths to lists of values");
  SectionRows rows = {{}};
  for (const auto& kv : grid) {
    const std::string key = kv.first.Scalar();
    reader.CheckVariedKey(kv.first, at.Child(key), key, "grid");
    parameters->push_back(key);
    const std::vector<std::string> values = reader.ReadList(kv.second, at.Child(key), key);
    CheckedProduct(rows.size(), values.size(), kv.first, at.Child(key));
    SectionRows next;
    for (const auto& row : rows) {  // the first key varies slowest
      for (const std::string& v : values) {
        next.push_back(row);
        next.back().push_back(v);
      }
    }
    rows = std::move(next);
  }
  return rows;
}

// `zip`: row i holds the i-th value of every key; the lists have equal lengths.
SectionRows ReadZipSection(const YAML::Node& zip, const ReadContext& at, SpecReader& reader,
                           std::vector<std::string>* parameters) {
  if (!zip.IsMap() || zip.size() == 0)
    Fail(zip, at, "expected a mapping of key paths to lists of values");
  SectionRows rows;
  std::string first_key;
  for (const auto& kv : zip) {
    const std::string key = kv.first.Scalar();
    reader.CheckVariedKey(kv.first, at.Child(key), key, "zip");
    parameters->push_back(key);
    const std::vector<std::string> values = reader.ReadList(kv.second, at.Child(key), key);
    if (first_key.empty()) {
      first_key = key;
      rows.resize(values.size());
    } else if (values.size() != rows.size()) {
      Fail(kv.second, at.Child(key),
           "has " + std::to_string(values.size()) + " values but zip." + first_key + " has " +
               std::to_string(rows.size()) + ": zipped lists must have equal lengths");
    }
    for (std::size_t i = 0; i < values.size(); ++i) rows[i].push_back(values[i]);
  }
  return rows;
}

// `random`: `samples` rows, each key's value drawn from its distribution with the section's seed.
SectionRows ReadRandomSection(const YAML::Node& random, const ReadContext& at, SpecReader& reader,
                              std::vector<std::string>* parameters) {
  if (!random.IsMap()) Fail(random, at, "expected {samples: N, seed: S, parameters: {...}}");
  io::internal::CheckKeys(random, at, {"samples", "seed", "parameters"});
  if (!random["samples"])
    Fail(random, at.Child("samples"), "missing: how many random combinations to draw");
  const auto samples = static_cast<std::size_t>(
      io::internal::ReadInteger(random["samples"], at.Child("samples"), 1, kMaxSamples));
  const std::uint64_t seed =
      random["seed"]
          ? static_cast<std::uint64_t>(io::internal::ReadInteger(
                random["seed"], at.Child("seed"), 0, std::numeric_limits<std::int64_t>::max()))
          : 1;
  const YAML::Node distribution_nodes = random["parameters"];
  const ReadContext pat = at.Child("parameters");
  if (!distribution_nodes || !distribution_nodes.IsMap() || distribution_nodes.size() == 0) {
    Fail(distribution_nodes ? distribution_nodes : random, pat,
         "expected a mapping of key paths to distributions");
  }
  std::vector<Distribution> distributions;
  for (const auto& kv : distribution_nodes) {
    const std::string key = kv.first.Scalar();
    reader.CheckVariedKey(kv.first, pat.Child(key), key, "random");
    parameters->push_back(key);
    distributions.push_back(ReadDistribution(reader, kv.second, pat.Child(key), key));
  }
  // Sample by sample, each parameter in file order: the draws depend on the seed alone.
  core::Rng rng(seed);
  SectionRows rows(samples);
  for (auto& row : rows) {
    for (const Distribution& d : distributions) row.push_back(d.Draw(rng));
  }
  return rows;
}

// A fixed key inside a varied one would be overwritten by it without a word.
void RequireFixedKeysNotVaried(const std::vector<Varied>& varied, const SweepSpec& spec,
                               const ReadContext& ctx) {
  for (const Varied& v : varied) {
    for (std::size_t i = 0; i < spec.fixed.size(); ++i) {
      const std::string& fixed_key = spec.fixed[i].key_path;
      if (fixed_key == v.key || IsPrefixKey(v.key, fixed_key)) {
        const std::string fixed_where =
            spec.fixed_sources[i].line > 0
                ? "`set` (line " + std::to_string(spec.fixed_sources[i].line) + ")"
                : "--set";
        Fail(v.key_node, ctx.Child(v.source.section).Child(v.key),
             "is varied, but '" + fixed_key + "' is also fixed by " + fixed_where);
      }
    }
  }
}

// The list under `key` (labels, plot), if given: varied parameters, each once.
void ReadVariedNames(const YAML::Node& root, const ReadContext& ctx, const char* key,
                     const std::vector<std::string>& parameters, std::vector<std::string>* out) {
  const YAML::Node node = root[key];
  if (!node) return;
  const ReadContext at = ctx.Child(key);
  if (!node.IsSequence()) Fail(node, at, "expected a list of varied parameters");
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string name = io::internal::ReadString(node[i], at.Element(i));
    if (std::find(parameters.begin(), parameters.end(), name) == parameters.end()) {
      Fail(node[i], at.Element(i),
           "'" + name + "' is not a varied parameter (in grid, zip or random)");
    }
    if (std::find(out->begin(), out->end(), name) != out->end())
      Fail(node[i], at.Element(i), "'" + name + "' is listed twice");
    out->push_back(name);
  }
}

// The combinations: the product of the sections, the first section outermost; with the repeats,
// no more cases than a sweep may have.
void ExpandCombinations(const std::vector<SectionRows>& section_rows, const YAML::Node& root,
                        const ReadContext& ctx, SweepSpec* spec) {
  spec->combinations = {{}};
  for (const auto& rows : section_rows) {
    CheckedProduct(spec->combinations.size() * static_cast<std::size_t>(spec->repeats), rows.size(),
                   root, ctx);
    SectionRows next;
    for (const auto& outer : spec->combinations) {
      for (const auto& inner : rows) {
        next.push_back(outer);
        next.back().insert(next.back().end(), inner.begin(), inner.end());
      }
    }
    spec->combinations = std::move(next);
  }
  CheckedProduct(spec->combinations.size(), static_cast<std::size_t>(spec->repeats), root, ctx);
}

// The metrics (listed, else the defaults), the timing ones apart; at least one not timing.
void ReadSweepMetrics(const YAML::Node& root, const ReadContext& ctx, SweepSpec* spec) {
  const std::vector<std::string> metrics =
      root["metrics"] ? ReadMetrics(root["metrics"], ctx.Child("metrics")) : DefaultSweepMetrics();
  for (const std::string& m : metrics)
    (IsTimingMetric(m) ? spec->timing_metrics : spec->metrics).push_back(m);
  if (spec->metrics.empty()) {
    Fail(root["metrics"], ctx.Child("metrics"),
         "lists only timing metrics (cpu.*); add at least one other");
  }
}

}  // namespace

MapMode SweepSpec::CombinationMode(std::size_t c) const {
  for (std::size_t p = 0; p < parameters.size(); ++p) {
    if (parameters[p] == "mode") return *core::ParseEnum<MapMode>(combinations.at(c)[p]);
  }
  return mode;
}

std::vector<io::ConfigOverride> SweepSpec::CombinationOverrides(std::size_t c) const {
  std::vector<io::ConfigOverride> out = fixed;
  for (std::size_t p = 0; p < parameters.size(); ++p) {
    if (parameters[p] == "mode" ||
        std::find(labels.begin(), labels.end(), parameters[p]) != labels.end())
      continue;
    out.push_back({parameters[p], combinations.at(c)[p]});
  }
  return out;
}

std::string SweepSpec::DescribeCombination(std::size_t c) const {
  std::string out;
  for (std::size_t p = 0; p < parameters.size(); ++p) {
    out += (p ? ", " : "") + parameters[p] + "=" + combinations.at(c)[p];
  }
  return out.empty() ? "no varied parameters" : out;
}

std::vector<std::string> DefaultSweepMetrics() {
  return {"success_rate", "tracking_error_m.pooled.rms", "localization_error_m.pooled.rms",
          "switch_error.max_m"};
}

const std::vector<std::string>& KnownSweepMetrics() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& [name, value] : FlatMetrics(AggregateMetrics{})) out.push_back(name);
    return out;
  }();
  return names;
}

SweepSpec LoadSweepSpec(const std::filesystem::path& file,
                        const std::vector<io::ConfigOverride>& cli_overrides) {
  const YAML::Node root = io::LoadYamlFile(file);
  SpecReader reader(file);
  const ReadContext& ctx = reader.ctx();
  if (!root.IsMap())
    Fail(root, ctx, "expected a mapping (see bench/sweep/sweep_spec.hpp for the format)");
  io::internal::CheckKeys(root, ctx,
                          {"name", "scenario", "mode", "set", "repeats", "grid", "zip", "random",
                           "labels", "plot", "metrics"});

  SweepSpec spec;
  spec.file = file;
  ReadSweepBasics(root, reader, &spec);
  ReadFixedOverrides(root, reader, cli_overrides, &spec);
  RequireFixedKeysOfScenario(spec, ctx);

  // The varied sections, each expanded into its own list of rows.
  std::vector<SectionRows> section_rows;
  if (const YAML::Node grid = root["grid"])
    section_rows.push_back(ReadGridSection(grid, ctx.Child("grid"), reader, &spec.parameters));
  if (const YAML::Node zip = root["zip"])
    section_rows.push_back(ReadZipSection(zip, ctx.Child("zip"), reader, &spec.parameters));
  if (const YAML::Node random = root["random"]) {
    section_rows.push_back(
        ReadRandomSection(random, ctx.Child("random"), reader, &spec.parameters));
  }
  for (const Varied& v : reader.varied()) spec.parameter_sources.push_back(v.source);
  RequireFixedKeysNotVaried(reader.varied(), spec, ctx);

  // Labels and plotted parameters name varied keys.
  ReadVariedNames(root, ctx, "labels", spec.parameters, &spec.labels);
  if (std::find(spec.labels.begin(), spec.labels.end(), "mode") != spec.labels.end()) {
    Fail(root["labels"], ctx.Child("labels"),
         "'mode' is applied to every case; it cannot be a label");
  }
  ReadVariedNames(root, ctx, "plot", spec.parameters, &spec.plot_parameters);
  if (!root["plot"]) spec.plot_parameters = spec.parameters;

  ExpandCombinations(section_rows, root, ctx, &spec);
  ReadSweepMetrics(root, ctx, &spec);
  return spec;
}

}  // namespace retrace::bench
