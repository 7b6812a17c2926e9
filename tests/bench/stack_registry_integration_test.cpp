// Stacks by name (bench/engine/stack_registry.hpp): a stack registered by a program drives a
// scenario's runs through `playback.stack`, with its declared options (defaults filled in), and a
// wrong name or option is refused naming the key.

#include <gtest/gtest.h>

#include <string>

#include "bench/engine/playback.hpp"
#include "bench/engine/retrace_stack.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/stack_registry.hpp"
#include "bench/engine/teach_drive.hpp"
#include "core/errors.hpp"
#include "io/config_override.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/trajectory_hash.hpp"

namespace retrace::bench {
namespace {

// retrace's stack behind a wrapper that counts its options' use: the registry hands it the
// options, and the run it drives is retrace's to the bit.
class WrappedStack final : public NavigationStack {
 public:
  explicit WrappedStack(const StackContext& c) : inner_(c.scenario, c.bundle, c.rng), options_(c.options) {}
  void OnOdometry(double t, const core::OdometryDelta& d) override { inner_.OnOdometry(t, d); }
  void OnScan(const core::LaserScan& scan) override { inner_.OnScan(scan); }
  StackOutput OnControlTick(double t, double dt) override { return inner_.OnControlTick(t, dt); }
  std::optional<MapChange> Resume(StackOutput* out) override { return inner_.Resume(out); }
  static inline StackOptions seen;

 private:
  RetraceStack inner_;
  StackOptions options_;
};

void RegisterWrappedStack() {
  static const bool done = [] {
    RegisterStack({"wrapped", "retrace's navigator behind a wrapper",
                   {{"gain", "1.0", "unused", StackOption::Kind::kNumber},
                    {"label", "none", "unused"}},
                   [](const StackContext& c) {
                     WrappedStack::seen = c.options;
                     return std::make_unique<WrappedStack>(c);
                   }});
    return true;
  }();
  (void)done;
}

Scenario RegistryScenario(const std::vector<std::string>& overrides = {}) {
  std::vector<io::ConfigOverride> parsed;
  for (const std::string& o : overrides) parsed.push_back(io::ParseOverride(o));
  return LoadScenario(retrace::testing::kSource / "scenarios/small.yaml", parsed);
}

// The message loading the small scenario with `overrides` fails with ("": it loads).
std::string RegistryError(const std::vector<std::string>& overrides) {
  try {
    RegistryScenario(overrides);
  } catch (const core::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(StackRegistry, ARegisteredStackDrivesTheRunsByNameWithItsOptions) {
  RegisterWrappedStack();
  const Scenario plain = RegistryScenario();
  const Scenario wrapped =
      RegistryScenario({"playback.stack=wrapped", "playback.stack_options.gain=2.5"});
  TeachResult teach = RunTeachDrive(plain, {MapMode::kPartial});
  const ModeTeach& t = teach.modes.front();
  const RunTrace a = RunPlayback(plain, t.bundle, t.trace, 0, 300.0);
  const RunTrace b = RunPlayback(wrapped, t.bundle, t.trace, 0, 300.0);
  EXPECT_EQ(retrace::testing::TrajectoryHash(a), retrace::testing::TrajectoryHash(b));
  EXPECT_EQ(WrappedStack::seen, (StackOptions{{"gain", "2.5"}, {"label", "none"}}));
  const std::vector<std::string> names = RegisteredStacks();
  EXPECT_EQ(names, (std::vector<std::string>{"odometry", "retrace", "wrapped"}));
}

TEST(StackRegistry, WrongNamesAndOptionsAreRefusedNamingTheKey) {
  RegisterWrappedStack();
  EXPECT_NE(RegistryError({"playback.stack=nope"})
                .find("playback.stack: unknown stack 'nope'; registered: odometry, retrace, "
                      "wrapped"),
            std::string::npos);
  EXPECT_NE(RegistryError({"playback.stack=wrapped", "playback.stack_options.gian=1"})
                .find("playback.stack_options.gian: stack 'wrapped' takes no option 'gian' (its "
                      "options: gain, label)"),
            std::string::npos);
  EXPECT_NE(RegistryError({"playback.stack_options.gain=1"})
                .find("stack 'retrace' takes no option 'gain' (it takes none)"),
            std::string::npos);
  EXPECT_THROW(RegisterStack({"retrace", "again", {}, [](const StackContext&) {
                                return std::unique_ptr<NavigationStack>();
                              }}),
               core::ConfigError);
}

TEST(StackRegistry, ANumberOptionIsCheckedWithTheScenarioAndReadByTheStack) {
  RegisterWrappedStack();
  for (const std::string bad : {"fast", "2.5x", "nan", "inf"}) {
    EXPECT_NE(RegistryError({"playback.stack=wrapped", "playback.stack_options.gain=" + bad})
                  .find("playback.stack_options.gain: '" + bad + "' is not a number"),
              std::string::npos)
        << bad;
  }
  EXPECT_EQ(RegistryError({"playback.stack=wrapped", "playback.stack_options.gain=-2e-1",
                      "playback.stack_options.label=x"}),
            "");
  const Scenario scenario = RegistryScenario({"playback.stack=wrapped"});
  const nav::TeachBundle bundle;
  StackContext context{scenario, bundle, 0, core::Rng(1), {{"gain", "-2e-1"}, {"label", "x"}}};
  EXPECT_EQ(context.Number("gain"), -0.2);
  EXPECT_THROW(context.Number("label"), core::ConfigError);
  EXPECT_THROW(context.Number("nope"), core::ConfigError);
  // A stack whose own default is not a number is refused when it registers.
  EXPECT_THROW(RegisterStack({"bad_default", "", {{"k", "one", "", StackOption::Kind::kNumber}},
                              [](const StackContext&) {
                                return std::unique_ptr<NavigationStack>();
                              }}),
               core::ConfigError);
}

}  // namespace
}  // namespace retrace::bench
