#include "bench/engine/switch_visibility.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bench/engine/switch_points.hpp"
#include "core/config.hpp"
#include "core/path_projection.hpp"
#include "core/rng.hpp"
#include "nav/scan_constraint.hpp"
#include "sim/lidar.hpp"

namespace retrace::bench {
namespace {

constexpr double kStep = 0.5;  // m between the places tried before a switch point

}  // namespace

std::vector<SwitchPlace> JudgeSwitchPlaces(const Scenario& scenario,
                                           const std::vector<double>& switch_points,
                                           double window) {
  std::vector<SwitchPlace> places;
  if (switch_points.empty()) return places;
  const sim::Lidar lidar(scenario.config.sim.lidar, scenario.teach_world.geometry);
  const std::vector<double> cum = core::CumulativeArcLength(scenario.route);
  auto constraint_at = [&](double s) {
    core::Rng rng(0);  // the same noise draw at every place: only the place differs
    const core::Pose2 X_WR = RoutePoseAt(scenario.route, cum, s);
    return nav::ScanConstraint(lidar.Scan(X_WR, {}, 0.0, rng).scan, scenario.robot);
  };
  for (std::size_t k = 0; k < switch_points.size(); ++k) {
    SwitchPlace place;
    place.s = switch_points[k];
    place.constraint = constraint_at(place.s);
    place.best_s = place.s;
    place.best_constraint = place.constraint;
    const double earliest = std::max(k == 0 ? 0.0 : switch_points[k - 1] + kStep, place.s - window);
    // Nearest first, so that of equal places the one closest to the switch point wins.
    for (double s = place.s - kStep; s >= earliest - 1e-9; s -= kStep) {
      const double c = constraint_at(s);
      if (c > place.best_constraint) {
        place.best_constraint = c;
        place.best_s = s;
      }
    }
    places.push_back(place);
  }
  return places;
}

std::vector<std::string> SwitchPlaceWarnings(const std::vector<SwitchPlace>& places,
                                             double minimum) {
  std::vector<std::string> warnings;
  for (std::size_t k = 0; k < places.size(); ++k) {
    const SwitchPlace& p = places[k];
    if (p.constraint >= minimum) continue;
    std::string w = "switch point " + std::to_string(k + 1) + " (" + ArcLengthText(p.s) +
                    ") sees little: a scan there constrains the pose by " +
                    core::FormatNumber(std::round(p.constraint)) +
                    " end points (route.min_switch_constraint " + core::FormatNumber(minimum) + ")";
    if (p.best_s != p.s) {
      w += "; at " + ArcLengthText(p.best_s) + " it would be " +
           core::FormatNumber(std::round(p.best_constraint));
    } else {
      w += "; no better place within route.switch_window before it";
    }
    warnings.push_back(w);
  }
  return warnings;
}

}  // namespace retrace::bench
