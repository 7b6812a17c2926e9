#pragma once
// Navigation stacks by name (`playback.stack`, docs/DESIGN.md §6): the built-ins register
// themselves (`retrace`, retrace's navigator; `odometry`, the taught paths replayed on dead
// reckoning), and a program that links the harness registers its own before it loads a scenario
// (examples/external_stack). Each stack declares its options, `playback.stack_options`: a key it
// does not declare is refused, the ones not given take their defaults. `run`, `compare`, `sweep`
// and `bench` drive whatever the scenario names.

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench/engine/scenario.hpp"
#include "bench/stack/navigation_stack.hpp"
#include "core/rng.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::bench {

/// `playback.stack_options`: option name → its value as written (YAML scalar text).
using StackOptions = std::map<std::string, std::string>;

/// One option a stack takes.
struct StackOption {
  /// kNumber: its text must read as a finite number (StackContext::Number), checked with the
  /// scenario, before anything runs.
  enum class Kind { kText, kNumber };
  std::string name;
  std::string default_value;
  std::string help;
  Kind kind = Kind::kText;
};

/// What a stack is built from for one playback run.
struct StackContext {
  const Scenario& scenario;
  /// The taught maps and paths, in route order (frames: map k starts at the teaching drive's
  /// odometry pose where it began map k; map 0's origin is where the run believes it starts).
  const nav::TeachBundle& bundle;
  int run = 0;
  core::Rng rng;        ///< the run's own randomness (PlaybackRng), for a stochastic stack
  StackOptions options;  ///< every declared option, given or default

  /// Option `name` read as a finite number. Throws core::ConfigError naming
  /// "playback.stack_options.<name>" when its text is not one (or the option is not declared).
  double Number(const std::string& name) const;
};

using StackFactory = std::function<std::unique_ptr<NavigationStack>(const StackContext&)>;

struct StackDescription {
  std::string name;
  std::string summary;              ///< one line, for error messages and `retrace run --help`
  std::vector<StackOption> options;
  StackFactory make;
  /// Its stacks offer NavigationStack::insight() (the video, the dynamic-point scoring).
  bool insight = false;
};

/// Registers a stack. Throws core::ConfigError("stack") for an empty or taken name, a missing
/// factory or an option declared twice.
void RegisterStack(StackDescription description);
/// The registered stacks' names, sorted.
std::vector<std::string> RegisteredStacks();
/// The stack registered as `name`; throws core::ConfigError("stack") naming the registered ones.
const StackDescription& FindStack(const std::string& name);
/// Throws core::ConfigError naming "stack" (unknown) or "stack_options.<key>" (not declared by
/// the stack) (keys relative to `playback`).
void ValidateStackChoice(const std::string& name, const StackOptions& options);
/// The stack playback run `run` of `scenario` drives with, on `bundle` (which must outlive it).
std::unique_ptr<NavigationStack> MakeStack(const Scenario& scenario, const nav::TeachBundle& bundle,
                                           int run);

}  // namespace retrace::bench
