#include "bench/engine/scripted_events.hpp"

#include <utility>

#include <algorithm>
#include <limits>

#include "core/errors.hpp"

namespace retrace::bench {

RouteProgress::RouteProgress(const std::vector<core::Vec2>& route)
    : route_(route), arc_(core::CumulativeArcLength(route)) {}

double RouteProgress::Update(const core::Vec2& p_W) {
  return progress_.Advance(route_, arc_, p_W, progress_.value() + kWindow);
}

ScriptedEvents::ScriptedEvents(const std::vector<EventConfig>& events, EventPhase phase) {
  for (const EventConfig& e : events) {
    if (e.phase == phase || e.phase == EventPhase::kBoth) pending_.push_back(e);
  }
}

std::vector<std::string> ScriptedEvents::Fire(double time, double route_s, sim::Simulator& sim) {
  std::vector<std::string> fired;
  for (auto it = pending_.begin(); it != pending_.end();) {
    const bool due =
        (it->at_time && time >= *it->at_time) || (it->at_route_s && route_s >= *it->at_route_s);
    if (!due) {
      ++it;
      continue;
    }
    const std::string name = it->name.empty() ? std::string(core::EnumName(it->action)) : it->name;
    try {
      switch (it->action) {
        case EventAction::kPedestrians:
          sim.AddPedestrians(it->pedestrians);
          break;
        case EventAction::kCrossing:
          sim.AddPedestrians(CrossingGroup(it->crossing));
          break;
        case EventAction::kObstacle:
          for (const sim::BoxConfig& box : it->boxes) sim.AddObstacle(box);
          for (const sim::CircleConfig& circle : it->circles) sim.AddObstacle(circle);
          break;
        case EventAction::kTakeover:
          takeover_ = it->drive;
          break;
      }
    } catch (const core::Error& e) {
      throw core::WorldError("scripted event '" + name + "': " + e.what());
    }
    fired.push_back(name);
    it = pending_.erase(it);
  }
  return fired;
}

std::vector<core::Vec2> ScriptedEvents::TakeOver() { return std::exchange(takeover_, {}); }

sim::PedestrianGroupConfig CrossingGroup(const CrossingConfig& crossing) {
  sim::PedestrianGroupConfig group;
  group.count = crossing.count;
  const core::Vec2 half(std::max(crossing.spread, 0.5), std::max(crossing.spread, 0.5));
  group.region_min = crossing.from - half;
  group.region_max = crossing.from + half;
  group.mode = sim::PedestrianMode::kLoop;
  group.waypoints = {crossing.to, crossing.from};
  group.speed_mean = crossing.speed_mean;
  group.speed_std = crossing.speed_std;
  return group;
}

}  // namespace retrace::bench
