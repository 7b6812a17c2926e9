#include "bench/metrics/switching.hpp"

#include "bench/engine/switch_points.hpp"

namespace retrace::bench {
namespace {

// m between the driven path's points kept: fine against the revisit radius (>= 0.4 m samples
// in CheckSwitchPoints for radii of 3 m and more), coarse enough to keep the check fast.
constexpr double kPathSpacing = 0.25;

}  // namespace

std::vector<std::string> SwitchReasons(const ModeTeach& teach, const RouteConfig& route) {
  std::vector<std::string> reasons;
  if (!SwitchesMaps(teach.mode) || teach.bundle.maps.size() < 2) return reasons;
  const std::size_t switches = teach.bundle.maps.size() - 1;
  if (route.switch_points.is(SwitchPlanning::kOnline)) {
    for (const nav::OnlineSwitch& s : teach.online_switches)
      reasons.emplace_back(core::EnumName(s.reason));
    // A teach folder read back holds no online switches: reasons unknown.
    if (reasons.size() != switches) reasons.clear();
    return reasons;
  }
  const char* why = route.switch_points.is(SwitchPlanning::kAuto) ? "auto" : "operator";
  reasons.assign(switches, why);
  return reasons;
}

SwitchingQuality EvaluateSwitching(const TeachTrace& trace, double revisit_radius,
                                   const std::vector<std::string>& reasons, double min_loop) {
  SwitchingQuality q;
  const bool with_reasons = reasons.size() + 1 == trace.maps.size();
  q.maps = static_cast<int>(trace.maps.size());
  // The driven path, thinned, with each map's first pose kept exactly; `travelled` is the arc
  // length of the thinned path.
  std::vector<core::Vec2> path;
  double travelled = 0.0;
  for (std::size_t k = 0; k < trace.maps.size(); ++k) {
    const TeachMapTrace& map = trace.maps[k];
    for (std::size_t i = 0; i < map.X_WR.size(); ++i) {
      const core::Vec2 p = map.X_WR[i].translation();
      if (path.empty()) {
        path.push_back(p);
      } else if (i == 0 || (p - path.back()).norm() >= kPathSpacing) {
        travelled += (p - path.back()).norm();
        path.push_back(p);
      }
      // A map that begins no farther along than the one before it holds no place at all.
      if (i == 0 && k > 0 && travelled > 0.0 &&
          (q.switch_travel_m.empty() || travelled > q.switch_travel_m.back())) {
        q.switch_travel_m.push_back(travelled);
        if (with_reasons) q.reasons.push_back(reasons[k - 1]);
      }
    }
  }
  if (path.size() < 2 || RouteLength(path) <= 0.0) {
    q.minimum = 1;
    return q;
  }
  // Switches at the path's very end (a map begun on the last pose) hold nothing.
  const double length = RouteLength(path);
  while (!q.switch_travel_m.empty() && !(q.switch_travel_m.back() < length)) {
    q.switch_travel_m.pop_back();
    if (with_reasons) q.reasons.pop_back();
  }
  for (const std::string& why : q.reasons) {
    if (why == "operator") ++q.reason_counts.operator_points;
    if (why == "auto") ++q.reason_counts.auto_points;
    if (why == "revisit") ++q.reason_counts.revisit;
    if (why == "drift_budget") ++q.reason_counts.drift_budget;
  }
  q.minimum = static_cast<int>(SuggestSwitchPoints(path, revisit_radius, min_loop).size()) + 1;
  q.warnings = CheckSwitchPoints(path, q.switch_travel_m, revisit_radius, min_loop);
  q.revisiting = static_cast<int>(q.warnings.size());
  return q;
}

}  // namespace retrace::bench
