#include "bench/engine/scripted_events.hpp"

#include <algorithm>
#include <limits>

#include "core/errors.hpp"

namespace retrace::bench {

RouteProgress::RouteProgress(const std::vector<core::Vec2>& route)
    : route_(route), arc_(route.size(), 0.0) {
  for (std::size_t i = 1; i < route_.size(); ++i)
    arc_[i] = arc_[i - 1] + (route_[i] - route_[i - 1]).norm();
}

double RouteProgress::Update(const core::Vec2& p_W) {
  const double limit = progress_ + kWindow;
  double best_s = progress_;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < route_.size(); ++i) {
    if (arc_[i + 1] < progress_) continue;
    if (arc_[i] > limit) break;
    const core::Vec2 a = route_[i], d = route_[i + 1] - route_[i];
    const double len = arc_[i + 1] - arc_[i];
    double t = std::clamp((p_W - a).dot(d) / (len * len), 0.0, 1.0);
    double s = arc_[i] + t * len;
    s = std::clamp(s, progress_, limit);  // stay inside the window
    const core::Vec2 q = a + d * ((s - arc_[i]) / len);
    const double d2 = (p_W - q).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best_s = s;
    }
  }
  progress_ = std::max(progress_, best_s);
  return progress_;
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
      }
    } catch (const core::Error& e) {
      throw core::WorldError("scripted event '" + name + "': " + e.what());
    }
    fired.push_back(name);
    it = pending_.erase(it);
  }
  return fired;
}

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
