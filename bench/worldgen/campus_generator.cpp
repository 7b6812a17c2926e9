#include "bench/worldgen/campus_generator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <utility>

#include "core/errors.hpp"
#include "core/rng.hpp"
#include "core/segment.hpp"
#include "sim/robot.hpp"
#include "sim/static_geometry.hpp"

namespace retrace::bench {
namespace {

using core::Vec2;

// ---- validation helpers ----------------------------------------------------------------------

void RequireRange(std::string_view key, const Range& r, bool allow_zero = false) {
  core::RequireFinite(key, r[0]);
  core::RequireFinite(key, r[1]);
  if (allow_zero ? !(r[0] >= 0.0) : !(r[0] > 0.0)) {
    throw core::ConfigError(std::string(key), std::string("the minimum must be ") +
                                                  (allow_zero ? ">= 0" : "> 0") + ", got " +
                                                  core::FormatNumber(r[0]));
  }
  if (!(r[0] <= r[1])) {
    throw core::ConfigError(std::string(key), "must be [min, max] with min <= max, got [" +
                                                  core::FormatNumber(r[0]) + ", " +
                                                  core::FormatNumber(r[1]) + "]");
  }
}

// Objects whose nominal offset lies inside the corridor would all be rejected: say so instead.
void RequireOutsideCorridor(std::string_view key, const Range& r, double corridor) {
  RequireRange(key, r);
  if (r[0] < corridor) {
    throw core::ConfigError(std::string(key), "must not start inside the corridor: the minimum " +
                                                  core::FormatNumber(r[0]) +
                                                  " m is below corridor_half_width (" +
                                                  core::FormatNumber(corridor) + " m)");
  }
}

// ---- geometry --------------------------------------------------------------------------------

double SegmentSegmentDistance(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1) {
  if (sim::SegmentsIntersect(a0, a1, b0, b1)) return 0.0;
  return std::min({core::SegmentDistance(a0, b0, b1), core::SegmentDistance(a1, b0, b1),
                   core::SegmentDistance(b0, a0, a1), core::SegmentDistance(b1, a0, a1)});
}

// The solid area an object takes: a circle, or a simple polygon with a bounding circle for
// quick rejection.
struct Footprint {
  std::vector<Vec2> ring;  // empty for a circle
  Vec2 center{0.0, 0.0};
  double radius = 0.0;  // the circle's radius, or the polygon's bounding radius
};

Footprint CircleFootprint(const Vec2& center, double radius) { return {{}, center, radius}; }

Footprint RingFootprint(std::vector<Vec2> ring) {
  Footprint f;
  for (const Vec2& p : ring) f.center += p;
  f.center /= static_cast<double>(ring.size());
  for (const Vec2& p : ring) f.radius = std::max(f.radius, (p - f.center).norm());
  f.ring = std::move(ring);
  return f;
}

double DistanceToSegment(const Footprint& f, const Vec2& a, const Vec2& b) {
  if (f.ring.empty()) return std::max(0.0, core::SegmentDistance(f.center, a, b) - f.radius);
  if (sim::PointInPolygon(f.ring, a)) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < f.ring.size(); ++i) {
    best = std::min(best, SegmentSegmentDistance(f.ring[i], f.ring[(i + 1) % f.ring.size()], a, b));
  }
  return best;
}

double Distance(const Footprint& f, const Footprint& g) {
  if (f.ring.empty() && g.ring.empty()) {
    return std::max(0.0, (f.center - g.center).norm() - f.radius - g.radius);
  }
  if (f.ring.empty()) return Distance(g, f);
  if (g.ring.empty()) {
    if (sim::PointInPolygon(f.ring, g.center)) return 0.0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < f.ring.size(); ++i) {
      best = std::min(best,
                      core::SegmentDistance(g.center, f.ring[i], f.ring[(i + 1) % f.ring.size()]));
    }
    return std::max(0.0, best - g.radius);
  }
  if (sim::PointInPolygon(f.ring, g.ring.front()) || sim::PointInPolygon(g.ring, f.ring.front())) {
    return 0.0;
  }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < f.ring.size(); ++i) {
    for (std::size_t j = 0; j < g.ring.size(); ++j) {
      best = std::min(best, SegmentSegmentDistance(f.ring[i], f.ring[(i + 1) % f.ring.size()],
                                                   g.ring[j], g.ring[(j + 1) % g.ring.size()]));
    }
  }
  return best;
}

// World-file numbers are rounded to 1 mm (and yaw to 0.1 mrad) so that the YAML stays short;
// footprints are built from the rounded values, so the checks hold for what is written.
double RoundMm(double v) { return std::round(v * 1000.0) / 1000.0; }
Vec2 RoundMm(const Vec2& p) { return {RoundMm(p.x()), RoundMm(p.y())}; }
double RoundYaw(double yaw) { return std::round(yaw * 10000.0) / 10000.0; }

// One piece of a thick polyline, as sim::BuildGeometry builds it (extended by half the
// thickness at both ends).
std::vector<Vec2> WallPieceRing(const Vec2& a, const Vec2& b, double thickness) {
  const double h = 0.5 * thickness;
  const Vec2 d = (b - a).normalized();
  const Vec2 nrm(-d.y(), d.x());
  const Vec2 a0 = a - h * d;
  const Vec2 b0 = b + h * d;
  return {a0 - h * nrm, b0 - h * nrm, b0 + h * nrm, a0 + h * nrm};
}

// ---- the route -------------------------------------------------------------------------------

// The route by arc length: positions, directions and stretches.
class RouteGeometry {
 public:
  explicit RouteGeometry(const std::vector<Vec2>& route) {
    for (const Vec2& p : route) {
      if (!p.allFinite()) throw core::WorldError("the route has a point that is not finite");
      // Repeated points would give zero-length segments without a direction.
      if (points_.empty() || (p - points_.back()).norm() > 1e-9) points_.push_back(p);
    }
    if (points_.size() < 2) {
      throw core::WorldError("the route needs at least 2 distinct points, got " +
                             std::to_string(points_.size()));
    }
    cum_.assign(points_.size(), 0.0);
    for (std::size_t i = 1; i < points_.size(); ++i) {
      cum_[i] = cum_[i - 1] + (points_[i] - points_[i - 1]).norm();
    }
  }

  double length() const { return cum_.back(); }
  const std::vector<Vec2>& points() const { return points_; }

  Vec2 PointAt(double s) const {
    const std::size_t i = SegmentAt(s);
    const double t = std::clamp((s - cum_[i]) / (cum_[i + 1] - cum_[i]), 0.0, 1.0);
    return points_[i] + t * (points_[i + 1] - points_[i]);
  }
  /// Unit direction of the segment at s.
  Vec2 TangentAt(double s) const {
    const std::size_t i = SegmentAt(s);
    return (points_[i + 1] - points_[i]).normalized();
  }
  /// Unit normal to the left of the direction of travel at s.
  Vec2 LeftAt(double s) const {
    const Vec2 t = TangentAt(s);
    return {-t.y(), t.x()};
  }
  /// Largest angle (rad) between the direction at s and the directions within `half` of arc
  /// length around it, sampled every metre: how far the route bends along a frontage.
  double BendAround(double s, double half) const {
    const Vec2 t = TangentAt(s);
    double worst = 0.0;
    for (double u = std::max(0.0, s - half); u <= std::min(length(), s + half); u += 1.0) {
      const Vec2 d = TangentAt(u);
      worst = std::max(worst, std::abs(std::atan2(t.x() * d.y() - t.y() * d.x(), t.dot(d))));
    }
    return worst;
  }
  /// The polyline of the route between arc lengths s0 < s1.
  std::vector<Vec2> Stretch(double s0, double s1) const {
    std::vector<Vec2> out{PointAt(s0)};
    for (std::size_t i = 0; i < points_.size(); ++i) {
      if (cum_[i] > s0 && cum_[i] < s1) out.push_back(points_[i]);
    }
    out.push_back(PointAt(s1));
    return out;
  }

 private:
  std::size_t SegmentAt(double s) const {
    const auto it = std::upper_bound(cum_.begin(), cum_.end(), s);
    const std::size_t i = it == cum_.begin() ? 0 : static_cast<std::size_t>(it - cum_.begin()) - 1;
    return std::min(i, points_.size() - 2);
  }

  std::vector<Vec2> points_;
  std::vector<double> cum_;
};

// ---- placement -------------------------------------------------------------------------------

// Decides whether an object fits: clear of every route segment (not only the one it decorates,
// so crossings and revisits stay open), of the bare stretches and of everything placed so far.
class Placer {
 public:
  Placer(const RouteGeometry& route, std::vector<std::vector<Vec2>> bare, double bare_radius,
         double gap)
      : route_(route), bare_(std::move(bare)), bare_radius_(bare_radius), gap_(gap) {}

  bool Fits(const Footprint& f, double route_clearance) const {
    if (!KeepsAway(f, route_.points(), route_clearance)) return false;
    for (const auto& stretch : bare_) {
      if (!KeepsAway(f, stretch, bare_radius_)) return false;
    }
    for (const Footprint& g : placed_) {
      if ((f.center - g.center).norm() - f.radius - g.radius >= gap_) continue;
      if (Distance(f, g) < gap_) return false;
    }
    return true;
  }
  void Add(Footprint f) { placed_.push_back(std::move(f)); }

 private:
  static bool KeepsAway(const Footprint& f, const std::vector<Vec2>& polyline, double distance) {
    for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
      const Vec2& a = polyline[i];
      const Vec2& b = polyline[i + 1];
      if (core::SegmentDistance(f.center, a, b) - f.radius >= distance) continue;
      if (DistanceToSegment(f, a, b) < distance) return false;
    }
    return true;
  }

  const RouteGeometry& route_;
  std::vector<std::vector<Vec2>> bare_;
  double bare_radius_;
  double gap_;
  std::vector<Footprint> placed_;
};

double Draw(core::Rng& rng, const Range& r) { return rng.Uniform(r[0], r[1]); }

// Calls place(s) at arc lengths spaced on average 100 m / per_100m apart, from a random start.
template <class F>
void AlongRoute(double length, double per_100m, core::Rng& rng, F place) {
  if (!(per_100m > 0.0)) return;
  const double mean_gap = 100.0 / per_100m;
  for (double s = rng.Uniform(0.0, mean_gap); s < length; s += mean_gap * rng.Uniform(0.5, 1.5)) {
    place(s);
  }
}

constexpr double kSides[] = {1.0, -1.0};  // left, right of the direction of travel
constexpr int kBuildingTries = 4;         // fresh sizes and setbacks before giving a spot up
constexpr double kHedgeStep = 2.0;        // m between hedge vertices along curves
constexpr double kMinHedgeLength = 3.0;   // m; shorter leftovers are dropped
// A building aligned with the route only looks planned where the route runs straight along
// its whole frontage; at corners it would stand askew.
constexpr double kMaxFrontageBend = 0.2;  // rad
// Inside a turn tighter than the offset, the offset curve folds back on itself; hedge pieces
// that stray this far from the route's direction are left out.
constexpr double kMaxHedgeDeviation = 0.8;  // rad

struct Generator {
  const RouteGeometry& route;
  const CampusConfig& config;
  Placer& placer;
  sim::WorldConfig& world;
  CampusStats& stats;

  void Buildings(core::Rng rng, double side) {
    const double clearance = std::max(config.corridor_half_width, config.building_setback[0]);
    AlongRoute(route.length(), config.buildings_per_100m, rng, [&](double s) {
      const Vec2 p = route.PointAt(s);
      const Vec2 t = route.TangentAt(s);
      const Vec2 n = side * route.LeftAt(s);
      for (int attempt = 0; attempt < kBuildingTries; ++attempt) {
        const double setback = Draw(rng, config.building_setback);
        const double width = Draw(rng, config.building_width);
        const double depth = Draw(rng, config.building_depth);
        const bool l_shape = rng.Bernoulli(config.building_l_shape_fraction);
        const double notch_x = width * rng.Uniform(0.35, 0.6);
        const double notch_y = depth * rng.Uniform(0.35, 0.6);
        const double notch_side = rng.Bernoulli(0.5) ? 1.0 : -1.0;
        const Vec2 center = RoundMm(Vec2(p + n * (setback + 0.5 * depth)));
        const double yaw = RoundYaw(std::atan2(t.y(), t.x()));
        if (route.BendAround(s, 0.5 * width) > kMaxFrontageBend) continue;
        if (!l_shape) {
          const sim::BoxConfig box{center, RoundMm(Vec2(width, depth)), yaw};
          Footprint f = RingFootprint(sim::BoxRing(box));
          if (!placer.Fits(f, clearance)) continue;
          placer.Add(std::move(f));
          world.boxes.push_back(box);
        } else {
          // An L: the box without one corner on the side away from the route, so that the
          // face towards the route stays straight.
          const double hx = 0.5 * width;
          const double hy = 0.5 * depth;
          const core::Pose2 X_WB(center.x(), center.y(), yaw);
          sim::PolygonConfig polygon;
          for (const Vec2& q :
               {Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(hx, hy - notch_y),
                Vec2(hx - notch_x, hy - notch_y), Vec2(hx - notch_x, hy), Vec2(-hx, hy)}) {
            // Mirror so that the notch faces away from the route (+y of the body is the left
            // of travel) on a random end.
            polygon.points.push_back(RoundMm(X_WB * Vec2(notch_side * q.x(), side * q.y())));
          }
          Footprint f = RingFootprint(polygon.points);
          if (!placer.Fits(f, clearance)) continue;
          placer.Add(std::move(f));
          world.polygons.push_back(std::move(polygon));
        }
        ++stats.buildings;
        return;
      }
    });
  }

  void Hedges(core::Rng rng, double side) {
    AlongRoute(route.length(), config.hedges_per_100m, rng, [&](double s0) {
      const double length = Draw(rng, config.hedge_length);
      const double offset = Draw(rng, config.hedge_offset);
      const double thickness = RoundMm(Draw(rng, config.hedge_thickness));
      const double s1 = std::min(s0 + length, route.length());
      // Vertices follow the route at a constant offset; near-duplicates (inside of a sharp
      // turn) are dropped, pieces that cut into the corridor are left out below.
      std::vector<Vec2> points;
      std::vector<double> at_s;  // arc length of each vertex
      for (double s = s0;; s += kHedgeStep) {
        const double at = std::min(s, s1);
        const Vec2 q = RoundMm(Vec2(route.PointAt(at) + side * offset * route.LeftAt(at)));
        if (points.empty() || (q - points.back()).norm() > 0.05) {
          points.push_back(q);
          at_s.push_back(at);
        }
        if (at >= s1) break;
      }
      // Split into runs of pieces that fit, each run one hedge.
      std::vector<Vec2> run;
      double run_length = 0.0;
      std::vector<Footprint> run_pieces;
      const auto flush = [&] {
        if (run.size() >= 2 && run_length >= kMinHedgeLength) {
          for (Footprint& f : run_pieces) placer.Add(std::move(f));
          world.walls.push_back({run, thickness, false});
          ++stats.hedges;
        }
        run.clear();
        run_pieces.clear();
        run_length = 0.0;
      };
      for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        Footprint piece = RingFootprint(WallPieceRing(points[i], points[i + 1], thickness));
        const Vec2 d = (points[i + 1] - points[i]).normalized();
        const Vec2 t = route.TangentAt(0.5 * (at_s[i] + at_s[i + 1]));
        const bool follows =
            std::abs(std::atan2(t.x() * d.y() - t.y() * d.x(), t.dot(d))) <= kMaxHedgeDeviation;
        if (!follows || !placer.Fits(piece, config.corridor_half_width)) {
          flush();
          continue;
        }
        if (run.empty()) run.push_back(points[i]);
        run.push_back(points[i + 1]);
        run_length += (points[i + 1] - points[i]).norm();
        run_pieces.push_back(std::move(piece));
      }
      flush();
    });
  }

  void TreeRows(core::Rng rng, double side) {
    AlongRoute(route.length(), config.tree_rows_per_100m, rng, [&](double s0) {
      const double s1 = std::min(s0 + Draw(rng, config.tree_row_length), route.length());
      const double offset = Draw(rng, config.tree_offset);
      const double spacing = Draw(rng, config.tree_spacing);
      for (double s = s0; s <= s1; s += spacing * rng.Uniform(0.9, 1.1)) {
        // Trees stand a little out of line, as planted ones do after a few decades.
        const double lateral = offset + rng.Uniform(-0.15, 0.15);
        const Vec2 c = RoundMm(Vec2(route.PointAt(s) + side * lateral * route.LeftAt(s)));
        const double r = RoundMm(Draw(rng, config.tree_radius));
        if (TryCircle(c, r)) ++stats.trees;
      }
    });
  }

  void Poles(core::Rng rng, double side) {
    AlongRoute(route.length(), config.poles_per_100m, rng, [&](double s) {
      const double offset = Draw(rng, config.pole_offset);
      const Vec2 c = RoundMm(Vec2(route.PointAt(s) + side * offset * route.LeftAt(s)));
      if (TryCircle(c, RoundMm(Draw(rng, config.pole_radius)))) ++stats.poles;
    });
  }

  void Benches(core::Rng rng, double side) {
    AlongRoute(route.length(), config.benches_per_100m, rng, [&](double s) {
      const double offset = Draw(rng, config.bench_offset);
      const Vec2 t = route.TangentAt(s);
      const sim::BoxConfig bench{RoundMm(Vec2(route.PointAt(s) + side * offset * route.LeftAt(s))),
                                 RoundMm(config.bench_size), RoundYaw(std::atan2(t.y(), t.x()))};
      Footprint f = RingFootprint(sim::BoxRing(bench));
      if (!placer.Fits(f, config.corridor_half_width)) return;
      placer.Add(std::move(f));
      world.boxes.push_back(bench);
      ++stats.benches;
    });
  }

  bool TryCircle(const Vec2& c, double r) {
    Footprint f = CircleFootprint(c, r);
    if (!placer.Fits(f, config.corridor_half_width)) return false;
    placer.Add(std::move(f));
    world.circles.push_back({c, r});
    return true;
  }
};

std::vector<Range> LandmarkPoorIntervals(const RouteGeometry& route, const CampusConfig& config,
                                         core::Rng rng) {
  const double length = route.length();
  std::vector<Range> out;
  for (std::size_t i = 0; i < config.landmark_poor_intervals.size(); ++i) {
    const Range& r = config.landmark_poor_intervals[i];
    // Arc lengths past the end are most likely meant for another route: say so.
    if (r[0] >= length) {
      throw core::ConfigError("landmark_poor_intervals[" + std::to_string(i) + "]",
                              "starts at " + core::FormatNumber(r[0]) +
                                  " m, beyond the end of the route (" +
                                  core::FormatNumber(RoundMm(length)) + " m)");
    }
    out.push_back({r[0], std::min(r[1], length)});
  }
  if (config.landmark_poor_fraction > 0.0) {
    const double stretch = std::min(config.landmark_poor_length, length);
    double covered = 0.0;
    // Random positions that keep half a stretch between stretches (so that they stay
    // separate); a short route may not fit them all.
    constexpr int kTries = 200;
    for (int i = 0; i < kTries && covered < config.landmark_poor_fraction * length; ++i) {
      const double a = rng.Uniform(0.0, length - stretch);
      const double b = a + stretch;
      const bool clear = std::all_of(out.begin(), out.end(), [&](const Range& r) {
        return b + 0.5 * stretch <= r[0] || a >= r[1] + 0.5 * stretch;
      });
      if (!clear) continue;
      out.push_back({RoundMm(a), RoundMm(b)});
      covered += stretch;
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

void AddPedestrians(const RouteGeometry& route, const CampusConfig& config, core::Rng rng,
                    sim::WorldConfig& world, CampusStats& stats) {
  const int groups = config.wander_groups + config.loop_groups;
  if (config.pedestrians <= 0 || groups <= 0) return;
  const double length = route.length();
  const auto count_of = [&](int g) {
    return config.pedestrians / groups + (g < config.pedestrians % groups ? 1 : 0);
  };
  // Wander groups: squares around points spread evenly along the route (jittered).
  for (int g = 0; g < config.wander_groups; ++g) {
    const double s = length * (g + rng.Uniform(0.25, 0.75)) / config.wander_groups;
    const Vec2 c = RoundMm(route.PointAt(s));
    const double h = 0.5 * config.wander_region_size;
    sim::PedestrianGroupConfig group;
    group.count = count_of(g);
    group.mode = sim::PedestrianMode::kWander;
    group.region_min = c - Vec2(h, h);
    group.region_max = c + Vec2(h, h);
    if (group.count > 0) world.pedestrians.push_back(group);
  }
  // Loop groups walk up and down a stretch of the route itself, meeting the robot head-on
  // and from behind.
  constexpr double kWaypointStep = 10.0;  // m
  constexpr double kRegionPadding = 2.0;  // m around the loop's waypoints
  for (int g = 0; g < config.loop_groups; ++g) {
    const double stretch = std::min(config.loop_length, length);
    const double s0 = (length - stretch) * (g + rng.Uniform(0.25, 0.75)) / config.loop_groups;
    sim::PedestrianGroupConfig group;
    group.count = count_of(config.wander_groups + g);
    group.mode = sim::PedestrianMode::kLoop;
    const int steps = std::max(1, static_cast<int>(std::ceil(stretch / kWaypointStep)));
    for (int k = 0; k <= steps; ++k) {
      group.waypoints.push_back(RoundMm(route.PointAt(s0 + stretch * k / steps)));
    }
    Vec2 lo = group.waypoints.front();
    Vec2 hi = lo;
    for (const Vec2& w : group.waypoints) {
      lo = lo.cwiseMin(w);
      hi = hi.cwiseMax(w);
    }
    group.region_min = lo - Vec2(kRegionPadding, kRegionPadding);
    group.region_max = hi + Vec2(kRegionPadding, kRegionPadding);
    if (group.count > 0) world.pedestrians.push_back(group);
  }
  stats.pedestrian_groups = static_cast<int>(world.pedestrians.size());
}

}  // namespace

void CampusConfig::Validate() const {
  const double robot_radius = sim::RobotConfig{}.radius;
  constexpr double kCorridorMargin = 0.1;
  core::RequireFinite("corridor_half_width", corridor_half_width);
  if (corridor_half_width < robot_radius + kCorridorMargin) {
    throw core::ConfigError("corridor_half_width",
                            "must be at least " +
                                core::FormatNumber(robot_radius + kCorridorMargin) +
                                " m (the robot's radius " + core::FormatNumber(robot_radius) +
                                " m plus a " + core::FormatNumber(kCorridorMargin) +
                                " m margin), got " + core::FormatNumber(corridor_half_width));
  }
  core::RequireNonNegative("object_gap", object_gap);
  for (const auto& [key, density] : {std::pair{"buildings_per_100m", buildings_per_100m},
                                     std::pair{"hedges_per_100m", hedges_per_100m},
                                     std::pair{"tree_rows_per_100m", tree_rows_per_100m},
                                     std::pair{"poles_per_100m", poles_per_100m},
                                     std::pair{"benches_per_100m", benches_per_100m}}) {
    core::RequireNonNegative(key, density);
  }
  RequireOutsideCorridor("building_setback", building_setback, corridor_half_width);
  RequireRange("building_width", building_width);
  RequireRange("building_depth", building_depth);
  core::RequireInRange("building_l_shape_fraction", building_l_shape_fraction, 0.0, 1.0);
  RequireOutsideCorridor("hedge_offset", hedge_offset, corridor_half_width);
  RequireRange("hedge_length", hedge_length);
  RequireRange("hedge_thickness", hedge_thickness);
  RequireRange("tree_row_length", tree_row_length, /*allow_zero=*/true);
  RequireOutsideCorridor("tree_offset", tree_offset, corridor_half_width);
  RequireRange("tree_spacing", tree_spacing);
  RequireRange("tree_radius", tree_radius);
  RequireOutsideCorridor("pole_offset", pole_offset, corridor_half_width);
  RequireRange("pole_radius", pole_radius);
  RequireOutsideCorridor("bench_offset", bench_offset, corridor_half_width);
  core::RequirePositive("bench_size", std::min(bench_size.x(), bench_size.y()));
  for (std::size_t i = 0; i < landmark_poor_intervals.size(); ++i) {
    const Range& r = landmark_poor_intervals[i];
    const std::string key = "landmark_poor_intervals[" + std::to_string(i) + "]";
    core::RequireFinite(key, r[0]);
    core::RequireFinite(key, r[1]);
    if (!(r[0] >= 0.0 && r[0] < r[1])) {
      throw core::ConfigError(key, "must be [from, to] arc lengths (m) with 0 <= from < to, got [" +
                                       core::FormatNumber(r[0]) + ", " + core::FormatNumber(r[1]) +
                                       "]");
    }
  }
  core::RequireInRange("landmark_poor_fraction", landmark_poor_fraction, 0.0, 0.5);
  core::RequirePositive("landmark_poor_length", landmark_poor_length);
  core::RequireNonNegative("landmark_poor_radius", landmark_poor_radius);
  core::RequireIntInRange("pedestrians", pedestrians, 0, 10000);
  core::RequireIntInRange("wander_groups", wander_groups, 0, 100);
  core::RequireIntInRange("loop_groups", loop_groups, 0, 100);
  if (pedestrians > 0 && wander_groups + loop_groups == 0) {
    throw core::ConfigError("wander_groups", "wander_groups + loop_groups must be >= 1 to place " +
                                                 std::to_string(pedestrians) + " pedestrians");
  }
  core::RequirePositive("wander_region_size", wander_region_size);
  core::RequirePositive("loop_length", loop_length);
}

sim::WorldConfig GenerateCampus(const std::vector<Vec2>& route_points, const CampusConfig& config,
                                std::uint64_t seed, CampusStats* stats_out) {
  config.Validate();
  const RouteGeometry route(route_points);
  const core::Rng rng(seed);

  CampusStats stats;
  stats.route_length = route.length();
  stats.landmark_poor_intervals = LandmarkPoorIntervals(route, config, rng.Split("landmark_poor"));
  std::vector<std::vector<Vec2>> bare;
  for (const Range& r : stats.landmark_poor_intervals) bare.push_back(route.Stretch(r[0], r[1]));

  sim::WorldConfig world;
  world.name = config.name;
  Placer placer(route, std::move(bare), config.landmark_poor_radius, config.object_gap);
  Generator gen{route, config, placer, world, stats};
  // Large things first, so that small ones fill in around them rather than block them.
  const core::Rng buildings = rng.Split("buildings");
  const core::Rng hedges = rng.Split("hedges");
  const core::Rng trees = rng.Split("trees");
  const core::Rng benches = rng.Split("benches");
  const core::Rng poles = rng.Split("poles");
  for (std::uint64_t i = 0; i < 2; ++i) gen.Buildings(buildings.Split(i), kSides[i]);
  for (std::uint64_t i = 0; i < 2; ++i) gen.Hedges(hedges.Split(i), kSides[i]);
  for (std::uint64_t i = 0; i < 2; ++i) gen.TreeRows(trees.Split(i), kSides[i]);
  for (std::uint64_t i = 0; i < 2; ++i) gen.Benches(benches.Split(i), kSides[i]);
  for (std::uint64_t i = 0; i < 2; ++i) gen.Poles(poles.Split(i), kSides[i]);
  AddPedestrians(route, config, rng.Split("pedestrians"), world, stats);

  if (stats_out != nullptr) *stats_out = std::move(stats);
  return world;
}

}  // namespace retrace::bench
