#pragma once
// Scripted events of a scenario, fired during one teaching drive or playback run when their
// trigger comes due: a time since the start, or the robot's progress along the route.

#include <string>
#include <vector>

#include "bench/engine/scenario.hpp"
#include "core/path_projection.hpp"
#include "core/pose2.hpp"
#include "sim/simulator.hpp"

namespace retrace::bench {

/// The robot's progress along the route (m of arc length), from ground truth: the closest route
/// point within a window ahead of the last progress, so that a route that revisits itself is
/// followed in order. Never decreases.
class RouteProgress {
 public:
  explicit RouteProgress(const std::vector<core::Vec2>& route);
  /// Moves the progress forward to the route point nearest p_W within kWindow ahead.
  double Update(const core::Vec2& p_W);
  double progress() const { return progress_.value(); }

  static constexpr double kWindow = 5.0;  ///< m searched ahead of the last progress

 private:
  std::vector<core::Vec2> route_;
  std::vector<double> arc_;
  core::ForwardProgress progress_;
};

class ScriptedEvents {
 public:
  /// Keeps the events of `phase` (and those of both phases), in file order.
  ScriptedEvents(const std::vector<EventConfig>& events, EventPhase phase);

  /// Fires every pending event whose trigger is due at time t (s) and progress s (m) on `sim`;
  /// returns the names of those fired. Throws core::WorldError when an event cannot be
  /// carried out (its pedestrians cannot be placed, its obstacle would hit the robot).
  std::vector<std::string> Fire(double time, double route_s, sim::Simulator& sim);
  /// The points of a takeover that fired since the last call (empty: none): the caller drives
  /// them (the simulator has no driver of its own).
  std::vector<core::Vec2> TakeOver();

 private:
  std::vector<EventConfig> pending_;
  std::vector<core::Vec2> takeover_;
};

/// The pedestrian group of a crossing: they appear around `from` and walk to `to` and back.
sim::PedestrianGroupConfig CrossingGroup(const CrossingConfig& crossing);

}  // namespace retrace::bench
