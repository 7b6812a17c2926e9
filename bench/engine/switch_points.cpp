#include "bench/engine/switch_points.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "core/check.hpp"
#include "core/config.hpp"
#include "core/errors.hpp"
#include "core/path_index.hpp"
#include "core/path_projection.hpp"
#include "nav/online_switcher.hpp"

namespace retrace::bench {
namespace {

using core::Vec2;

using core::CumulativeArcLength;

struct Revisit {
  double s = 0.0;          // first sample that revisits
  double s_before = 0.0;   // the sample before it (still fine)
  double s_earlier = 0.0;  // where the route was before, within the radius
};

// The first sample of the stretch [s_start, s_end] that comes within revisit_radius of an
// earlier part of the same stretch lying more than nav::RevisitLag(revisit_radius), and more than
// min_loop, of travel behind. Samples are s_start + i·step and s_end, so CheckSwitchPoints and
// SuggestSwitchPoints see the same points.
std::optional<Revisit> FirstRevisit(const std::vector<Vec2>& route, const std::vector<double>& cum,
                                    const core::PathIndex& index, double s_start, double s_end,
                                    double revisit_radius, double min_loop) {
  const double step = nav::RevisitSampleStep(revisit_radius);
  const double lag = std::max(nav::RevisitLag(revisit_radius), min_loop);
  double previous = s_start;
  for (long i = 0;; ++i) {
    double s = s_start + static_cast<double>(i) * step;
    const bool last = s >= s_end;
    if (last) s = s_end;
    if (s - lag > s_start) {
      const core::PathProjection earlier =
          index.Project(RoutePoseAt(route, cum, s).translation(), s_start, s - lag);
      if (earlier.distance < revisit_radius) return Revisit{s, previous, earlier.s};
    }
    if (last) return std::nullopt;
    previous = s;
  }
}

void RequireUsable(const std::vector<Vec2>& route, double revisit_radius) {
  if (route.size() < 2) {
    throw core::ConfigError("route",
                            "needs at least 2 points, got " + std::to_string(route.size()));
  }
  core::RequirePositive("revisit_radius", revisit_radius);
}

}  // namespace

core::Pose2 RoutePoseAt(const std::vector<Vec2>& route, const std::vector<double>& cum, double s) {
  std::size_t i =
      static_cast<std::size_t>(std::upper_bound(cum.begin(), cum.end(), s) - cum.begin());
  i = std::clamp<std::size_t>(i, 1, route.size() - 1) - 1;
  const Vec2 d = route[i + 1] - route[i];
  const double len = cum[i + 1] - cum[i];
  const double t = len > 0.0 ? std::clamp((s - cum[i]) / len, 0.0, 1.0) : 0.0;
  const Vec2 p = route[i] + t * d;
  return core::Pose2(p.x(), p.y(), std::atan2(d.y(), d.x()));
}

std::string ArcLengthText(double s) {
  return core::FormatNumber(std::round(s * 10.0) / 10.0) + " m";
}

double RouteLength(const std::vector<Vec2>& route) {
  double length = 0.0;
  for (std::size_t i = 1; i < route.size(); ++i) length += (route[i] - route[i - 1]).norm();
  return length;
}

std::vector<std::string> CheckSwitchPoints(const std::vector<Vec2>& route,
                                           const std::vector<double>& switch_points,
                                           double revisit_radius, double min_loop) {
  RequireUsable(route, revisit_radius);
  const std::vector<double> cum = CumulativeArcLength(route);
  const double length = cum.back();
  for (std::size_t i = 0; i < switch_points.size(); ++i) {
    const double s = switch_points[i];
    const std::string which =
        "switch point " + std::to_string(i) + " (" + core::FormatNumber(s) + ")";
    if (!(s > 0.0) || !(s < length)) {
      throw core::ConfigError("route.switch_points",
                              which + " must lie inside the route, between 0 and its length " +
                                  ArcLengthText(length) + " (exclusive)");
    }
    if (i > 0 && !(s > switch_points[i - 1])) {
      throw core::ConfigError("route.switch_points",
                              which + " must be greater than the one before it (" +
                                  core::FormatNumber(switch_points[i - 1]) +
                                  "): switch points are arc lengths in increasing order");
    }
  }

  const core::PathIndex index(route, cum, revisit_radius);
  std::vector<std::string> warnings;
  for (std::size_t k = 0; k <= switch_points.size(); ++k) {
    const double s_start = k == 0 ? 0.0 : switch_points[k - 1];
    const double s_end = k == switch_points.size() ? length : switch_points[k];
    const auto revisit =
        FirstRevisit(route, cum, index, s_start, s_end, revisit_radius, min_loop);
    if (!revisit) continue;
    std::ostringstream msg;
    msg << "partial map " << k << " (route " << ArcLengthText(s_start) << " to "
        << ArcLengthText(s_end) << ") revisits its own path from " << ArcLengthText(revisit->s)
        << " on (within " << core::FormatNumber(revisit_radius) << " m of where it was at "
        << ArcLengthText(revisit->s_earlier)
        << "): the switch is too late; start the next map before " << ArcLengthText(revisit->s);
    warnings.push_back(msg.str());
  }
  return warnings;
}

std::vector<double> SuggestSwitchPoints(const std::vector<Vec2>& route, double revisit_radius,
                                        double min_loop) {
  RequireUsable(route, revisit_radius);
  const std::vector<double> cum = CumulativeArcLength(route);
  const core::PathIndex index(route, cum, revisit_radius);
  std::vector<double> points;
  double s_start = 0.0;
  while (const auto revisit =
             FirstRevisit(route, cum, index, s_start, cum.back(), revisit_radius, min_loop)) {
    // The last sample before the revisit: the map ending there is still clean, and it lies at
    // least (lag - step) beyond s_start, so the loop advances.
    points.push_back(revisit->s_before);
    s_start = revisit->s_before;
  }
  return points;
}

}  // namespace retrace::bench
