#include "bench/sweep/sweep_plan.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <limits>
#include <set>

#include "bench/engine/parallel.hpp"
#include "bench/engine/scenario.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "io/read_file.hpp"

namespace retrace::bench {
namespace {

constexpr int kMaxShards = 100000;

// "events[0].pedestrians" (a reader's key path) as an override writes it: "events.0.pedestrians".
std::string DottedPath(std::string path) {
  for (char& c : path) {
    if (c == '[') c = '.';
  }
  std::erase(path, ']');
  return path;
}

bool SameOrInside(const std::string& outer, const std::string& inner) {
  return inner == outer ||
         (inner.size() > outer.size() && inner.compare(0, outer.size(), outer) == 0 &&
          inner[outer.size()] == '.');
}

// The message of a scenario error without the "<scenario> (--set k=v): " or "--set k=v: " that
// the scenario loader puts in front of errors caused by an override: in a sweep the override
// comes from the sweep file, which the new message names instead.
std::string WithoutOverridePrefix(const std::string& message, const io::ConfigOverride& o) {
  const std::string set = "--set " + o.key_path + "=" + o.value;
  for (const std::string& marker : {"(" + set + "): ", set + ": "}) {
    const std::size_t at = message.find(marker);
    if (at != std::string::npos) return message.substr(at + marker.size());
  }
  return message;
}

// Rewrites a scenario loading error of combination c so that it names the sweep file and the
// line of the key that caused it, when one did.
[[noreturn]] void FailCombination(const SweepSpec& spec, std::size_t c, const core::Error& e) {
  const std::string sweep = spec.file.string();
  const std::string with =
      "scenario " + spec.scenario.string() + ", with " + spec.DescribeCombination(c);
  if (const auto* config_error = dynamic_cast<const core::ConfigError*>(&e);
      config_error && !config_error->key_path().empty()) {
    const std::string path = DottedPath(config_error->key_path());
    // The last override wins in the scenario, so search from the back.
    const std::vector<io::ConfigOverride> overrides = spec.CombinationOverrides(c);
    for (std::size_t i = overrides.size(); i-- > 0;) {
      const io::ConfigOverride& o = overrides[i];
      if (!SameOrInside(o.key_path, path) && !SameOrInside(path, o.key_path)) continue;
      SweepKeySource source;
      if (i < spec.fixed.size()) {
        source = spec.fixed_sources[i];
      } else {
        for (std::size_t p = 0; p < spec.parameters.size(); ++p) {
          if (spec.parameters[p] == o.key_path) source = spec.parameter_sources[p];
        }
      }
      const std::string where = source.line > 0
                                    ? sweep + ":" + std::to_string(source.line)
                                    : sweep + " (--set " + o.key_path + "=" + o.value + ")";
      throw core::ConfigError(
          o.key_path, where + ": " + WithoutOverridePrefix(e.what(), o) + " (" + with + ")", true);
    }
  }
  throw core::ConfigError(
      "", sweep + ": combination " + std::to_string(c) + " (" + with + "): " + e.what(), true);
}

std::string Hex(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(value));
  return text;
}

// Everything that decides a sweep's results, as text: a change to any of it makes another sweep.
std::string IdentityText(const SweepPlan& plan, const std::vector<std::uint64_t>& file_hashes) {
  const SweepSpec& s = plan.spec;
  std::string text = "retrace sweep 1\nmode " + std::string(core::EnumName(s.mode)) + "\nrepeats " +
                     std::to_string(s.repeats) + "\n";
  auto list = [&text](const char* what, const std::vector<std::string>& items) {
    text += what;
    for (const std::string& item : items) text += "\x1f" + item;
    text += "\n";
  };
  for (const io::ConfigOverride& o : s.fixed) list("fixed", {o.key_path, o.value});
  list("parameters", s.parameters);
  list("labels", s.labels);
  for (std::size_t c = 0; c < s.combinations.size(); ++c) {
    list(("combination " + std::to_string(plan.base_seeds[c])).c_str(), s.combinations[c]);
  }
  list("metrics", s.metrics);
  list("timing_metrics", s.timing_metrics);
  for (const std::uint64_t hash : file_hashes) text += "file " + Hex(hash) + "\n";
  return text;
}

}  // namespace

std::size_t SweepShard::CaseCount(std::size_t total) const {
  const auto n = static_cast<std::size_t>(count);
  const auto i = static_cast<std::size_t>(index - 1);
  return total / n + (i < total % n ? 1 : 0);
}

std::string SweepShard::ToString() const {
  return std::to_string(index) + "/" + std::to_string(count);
}

SweepShard ParseShard(std::string_view text) {
  auto fail = [&]() -> SweepShard {
    throw core::ConfigError(
        "--shard", "expected i/N with 1 <= i <= N (e.g. 2/8), got '" + std::string(text) + "'");
  };
  const std::size_t slash = text.find('/');
  if (slash == std::string_view::npos) return fail();
  SweepShard shard;
  const std::string_view a = text.substr(0, slash), b = text.substr(slash + 1);
  const auto ra = std::from_chars(a.data(), a.data() + a.size(), shard.index);
  const auto rb = std::from_chars(b.data(), b.data() + b.size(), shard.count);
  if (ra.ec != std::errc() || ra.ptr != a.data() + a.size() || rb.ec != std::errc() ||
      rb.ptr != b.data() + b.size()) {
    return fail();
  }
  if (shard.count < 1 || shard.count > kMaxShards || shard.index < 1 || shard.index > shard.count)
    return fail();
  return shard;
}

std::vector<io::ConfigOverride> SweepPlan::CaseOverrides(std::size_t case_id) const {
  std::vector<io::ConfigOverride> out = spec.CombinationOverrides(combination(case_id));
  out.push_back({"seed", std::to_string(seed(case_id))});
  out.push_back({"playback.repeats", "1"});
  return out;
}

SweepPlan PlanSweep(SweepSpec spec, int jobs) {
  SweepPlan plan;
  plan.spec = std::move(spec);
  const SweepSpec& s = plan.spec;
  const std::size_t combinations = s.combinations.size();
  plan.base_seeds.resize(combinations);
  std::vector<std::vector<std::filesystem::path>> files(combinations);
  std::vector<std::vector<std::string>> warnings(combinations);
  ParallelFor(jobs, combinations, [&](std::size_t c) {
    try {
      const Scenario scenario = LoadScenario(s.scenario, s.CombinationOverrides(c));
      plan.base_seeds[c] = scenario.config.seed;
      warnings[c] = scenario.warnings;
      files[c].push_back(scenario.teach_world.source);
      if (!scenario.config.route.file.empty()) {
        files[c].push_back(s.scenario.parent_path() / scenario.config.route.file);
      }
    } catch (const core::Error& e) {
      FailCombination(s, c, e);
    }
    // Seeds are read as signed 64-bit integers: the last repeat's must still be one.
    const auto max_seed = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
    if (plan.base_seeds[c] > max_seed - static_cast<std::uint64_t>(s.repeats - 1)) {
      throw core::ConfigError("seed",
                              s.file.string() + ": combination " + std::to_string(c) + ": seed " +
                                  std::to_string(plan.base_seeds[c]) + " + repeats overflows",
                              true);
    }
  });
  // The input files by their contents (not their paths, which depend on the working folder),
  // sorted, so that the identity does not depend on which combination named a file first.
  auto content_hash = [](const std::filesystem::path& file) {
    const std::string bytes = io::ReadFileBytes(file);
    return core::HashBytes(bytes.data(), bytes.size());
  };
  std::set<std::filesystem::path> seen;
  std::set<std::uint64_t> others;
  for (const auto& list : files) {
    for (const std::filesystem::path& f : list) {
      if (seen.insert(f.lexically_normal()).second) others.insert(content_hash(f));
    }
  }
  for (const auto& list : warnings) {
    for (const std::string& w : list) {
      if (std::find(plan.warnings.begin(), plan.warnings.end(), w) == plan.warnings.end())
        plan.warnings.push_back(w);
    }
  }
  std::vector<std::uint64_t> file_hashes = {content_hash(s.scenario)};
  file_hashes.insert(file_hashes.end(), others.begin(), others.end());
  const std::string text = IdentityText(plan, file_hashes);
  plan.identity = Hex(core::HashBytes(text.data(), text.size()));
  return plan;
}

}  // namespace retrace::bench
