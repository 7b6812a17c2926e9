#pragma once
// retrace's own navigation stack behind the playback loop's interface: the navigator
// (localizer, map server, path follower; nav/navigator.hpp) and obstacle avoidance on the latest
// scan. It lets the harness look at its localizer (StackInsight).

#include <memory>
#include <optional>

#include "bench/stack/navigation_stack.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/stack_insight.hpp"
#include "core/rng.hpp"
#include "nav/navigator.hpp"
#include "nav/obstacle_avoidance.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::bench {

class RetraceStack final : public NavigationStack, public StackInsight {
 public:
  /// The navigator on `bundle` with the scenario's nav config, believing the robot is at map 0's
  /// origin (playback.initial_sigma_*); its randomness from rng.Split("localizer").
  RetraceStack(const Scenario& scenario, const nav::TeachBundle& bundle, const core::Rng& rng);

  void OnOdometry(double t, const core::OdometryDelta& delta) override;
  void OnScan(const core::LaserScan& scan) override;
  StackOutput OnControlTick(double t, double dt) override;
  std::optional<MapChange> Resume(StackOutput* out) override;
  const StackInsight* insight() const override { return this; }

  const nav::LocalizerUpdate* last_update() const override { return &update_; }
  const nav::Localizer& localizer() const override { return nav_.localizer(); }
  const nav::MapServer& server() const override { return nav_.server(); }

 private:
  // The navigator's state into out (all but the command and the tick's switch).
  void Report(StackOutput* out) const;

  nav::Navigator nav_;
  nav::ObstacleAvoidance avoidance_;
  nav::LocalizerUpdate update_;
  std::optional<core::LaserScan> latest_scan_;
};

}  // namespace retrace::bench
