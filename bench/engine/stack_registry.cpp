#include "bench/engine/stack_registry.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <mutex>
#include <optional>
#include <set>
#include <utility>

#include "bench/engine/odometry_stack.hpp"
#include "bench/engine/playback.hpp"
#include "bench/engine/retrace_stack.hpp"
#include "core/errors.hpp"

namespace retrace::bench {
namespace {

struct Registry {
  std::mutex mutex;
  std::map<std::string, StackDescription> stacks;
};

// `text` read as a finite number (all of it), or nothing.
std::optional<double> NumberOf(const std::string& text) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

// An option's text as a finite number, or core::ConfigError naming `key`.
double ReadNumber(const std::string& key, const std::string& text) {
  const std::optional<double> value = NumberOf(text);
  if (!value) throw core::ConfigError(key, "'" + text + "' is not a number");
  return *value;
}

void Add(Registry& r, StackDescription d) {
  if (d.name.empty()) throw core::ConfigError("stack", "a stack needs a name");
  if (!d.make) throw core::ConfigError("stack", "stack '" + d.name + "' has no factory");
  std::set<std::string> names;
  for (const StackOption& o : d.options) {
    if (!names.insert(o.name).second) {
      throw core::ConfigError("stack", "stack '" + d.name + "' declares option '" + o.name +
                                           "' twice");
    }
    if (o.kind == StackOption::Kind::kNumber && !NumberOf(o.default_value)) {
      throw core::ConfigError("stack", "stack '" + d.name + "' gives option '" + o.name +
                                           "' the default '" + o.default_value +
                                           "', which is not a number");
    }
  }
  const std::string name = d.name;
  if (!r.stacks.emplace(name, std::move(d)).second) {
    throw core::ConfigError("stack", "a stack named '" + name + "' is registered already");
  }
}

// The registry, with the built-ins in it from the first use on.
Registry& TheRegistry() {
  static Registry* registry = [] {
    auto* r = new Registry;
    Add(*r, {"retrace", "retrace's navigator: MCL in the taught maps, the map server, the path "
                        "follower and obstacle avoidance (nav.*)",
             {},
             [](const StackContext& c) {
               return std::make_unique<RetraceStack>(c.scenario, c.bundle, c.rng);
             },
             true});
    Add(*r, {"odometry", "the taught paths replayed on dead reckoning, no localization",
             {},
             [](const StackContext& c) {
               return std::make_unique<OdometryStack>(c.scenario, c.bundle);
             },
             false});
    return r;
  }();
  return *registry;
}

std::string NameList(const Registry& r) {
  std::string out;
  for (const auto& [name, d] : r.stacks) out += (out.empty() ? "" : ", ") + name;
  return out;
}

}  // namespace

double StackContext::Number(const std::string& name) const {
  const auto it = options.find(name);
  if (it == options.end()) {
    throw core::ConfigError("playback.stack_options." + name, "the stack declares no such option");
  }
  return ReadNumber("playback.stack_options." + name, it->second);
}

void RegisterStack(StackDescription description) {
  Registry& r = TheRegistry();
  const std::lock_guard lock(r.mutex);
  Add(r, std::move(description));
}

std::vector<std::string> RegisteredStacks() {
  Registry& r = TheRegistry();
  const std::lock_guard lock(r.mutex);
  std::vector<std::string> names;
  for (const auto& [name, d] : r.stacks) names.push_back(name);
  return names;
}

const StackDescription& FindStack(const std::string& name) {
  Registry& r = TheRegistry();
  const std::lock_guard lock(r.mutex);
  const auto it = r.stacks.find(name);
  if (it == r.stacks.end()) {
    throw core::ConfigError("stack", "unknown stack '" + name + "'; registered: " + NameList(r));
  }
  return it->second;  // entries are never removed: the reference stays valid
}

void ValidateStackChoice(const std::string& name, const StackOptions& options) {
  const StackDescription& d = FindStack(name);
  for (const auto& option : options) {
    const std::string& key = option.first;
    const bool declared = std::any_of(d.options.begin(), d.options.end(),
                                      [&](const StackOption& o) { return o.name == key; });
    if (declared) continue;
    std::string known;
    for (const StackOption& o : d.options) known += (known.empty() ? "" : ", ") + o.name;
    throw core::ConfigError("stack_options." + key,
                            "stack '" + name + "' takes no option '" + key + "' (" +
                                (known.empty() ? "it takes none" : "its options: " + known) + ")");
  }
  for (const StackOption& o : d.options) {
    const auto given = options.find(o.name);
    if (o.kind == StackOption::Kind::kNumber && given != options.end()) {
      ReadNumber("stack_options." + o.name, given->second);
    }
  }
}

std::unique_ptr<NavigationStack> MakeStack(const Scenario& scenario, const nav::TeachBundle& bundle,
                                           int run) {
  const PlaybackConfig& p = scenario.config.playback;
  const StackDescription& d = FindStack(p.stack);
  StackContext context{scenario, bundle, run, PlaybackRng(scenario.config, run), {}};
  for (const StackOption& o : d.options) {
    const auto given = p.stack_options.find(o.name);
    context.options[o.name] = given != p.stack_options.end() ? given->second : o.default_value;
  }
  return d.make(context);
}

}  // namespace retrace::bench
