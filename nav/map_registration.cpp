#include "nav/map_registration.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace retrace::nav {
namespace {

// Map B's occupied cell centres within `radius` of p_B, evenly thinned to at most max_points.
std::vector<core::Vec2> CellsNear(const core::OccupancyGrid& grid, const core::Vec2& p,
                                  double radius, double occupied_threshold, int max_points) {
  std::vector<core::Vec2> cells;
  if (grid.empty()) return cells;
  const float occupied = static_cast<float>(core::Logit(occupied_threshold));
  const core::CellIndex lo = grid.WorldToCell(p - core::Vec2(radius, radius));
  const core::CellIndex hi = grid.WorldToCell(p + core::Vec2(radius, radius));
  for (int y = std::max(lo.y, 0); y <= std::min(hi.y, grid.height() - 1); ++y) {
    for (int x = std::max(lo.x, 0); x <= std::min(hi.x, grid.width() - 1); ++x) {
      const core::CellIndex c{x, y};
      if (grid.LogOdds(c) < occupied) continue;
      const core::Vec2 q = grid.CellToWorld(c);
      if ((q - p).norm() <= radius) cells.push_back(q);
    }
  }
  if (static_cast<int>(cells.size()) <= max_points) return cells;
  std::vector<core::Vec2> thinned(static_cast<std::size_t>(max_points));
  for (std::size_t i = 0; i < thinned.size(); ++i)
    thinned[i] = cells[i * cells.size() / thinned.size()];
  return thinned;
}

// Cells of B scored in the coarse search (the fine one scores all of them).
constexpr std::size_t kCoarsePoints = 150;

// A candidate transform: the prior turned by dtheta about the place (so that a turn does not
// also move the place), then shifted by (dx, dy).
struct Offset {
  double dx = 0.0, dy = 0.0, dtheta = 0.0;
};

core::Pose2 Apply(const core::Pose2& prior, const core::Vec2& q_A, const Offset& o) {
  const core::Pose2 turn = core::Pose2(q_A.x(), q_A.y(), 0.0) * core::Pose2(0.0, 0.0, o.dtheta) *
                           core::Pose2(-q_A.x(), -q_A.y(), 0.0);
  return core::Pose2(o.dx, o.dy, 0.0) * turn * prior;
}

struct Score {
  double log_likelihood = 0.0;
  int inliers = 0;
};

Score ScoreOf(const LikelihoodField& field, const std::vector<core::Vec2>& points,
              const core::Pose2& X_AB, float inlier_log_likelihood) {
  Score s;
  const double c = std::cos(X_AB.theta), sn = std::sin(X_AB.theta);
  for (const core::Vec2& p : points) {
    const core::Vec2 q(X_AB.x + c * p.x() - sn * p.y(), X_AB.y + sn * p.x() + c * p.y());
    const float ll = field.LogLikelihood(q);
    s.log_likelihood += ll;
    s.inliers += ll >= inlier_log_likelihood ? 1 : 0;
  }
  return s;
}

struct Tried {
  Offset offset;
  Score score;
};

bool Better(const Tried& a, const Tried& b) {
  return a.score.log_likelihood < b.score.log_likelihood;
}

// Scores offsets of the prior X_AB, turned about the place q_A (in A).
struct Scorer {
  const LikelihoodField& field;
  const core::Pose2& prior;
  core::Vec2 q_A;

  Tried operator()(const std::vector<core::Vec2>& points, const Offset& o,
                   float inlier_ll) const {
    return {o, ScoreOf(field, points, Apply(prior, q_A, o), inlier_ll)};
  }
};

// The coarse search: the whole window with a subset of the cells, each pose's inliers counted
// within a distance widened by half the step's diagonal, so that the grid's best pose is not
// short of inliers only for lying between two steps. The best pose, the best inlier count of
// the poses ambiguity_distance or more away from it, and the subset's size.
struct Coarse {
  Tried best;
  int runner_up = 0;
  int points = 0;
};

Coarse CoarseSearch(const Scorer& score, const std::vector<core::Vec2>& points,
                    const MapRegistrationConfig& config) {
  const std::size_t stride = (points.size() + kCoarsePoints - 1) / kCoarsePoints;
  std::vector<core::Vec2> subset;
  for (std::size_t i = 0; i < points.size(); i += stride) subset.push_back(points[i]);
  const float inlier_ll = static_cast<float>(score.field.LogLikelihoodOfDistance(
      config.inlier_distance + config.coarse_xy / std::sqrt(2.0)));
  std::vector<Tried> tried;
  const int nxy = static_cast<int>(std::floor(config.search_xy / config.coarse_xy));
  const int nth = static_cast<int>(std::floor(config.search_theta / config.coarse_theta));
  for (int it = -nth; it <= nth; ++it) {
    for (int iy = -nxy; iy <= nxy; ++iy) {
      for (int ix = -nxy; ix <= nxy; ++ix) {
        tried.push_back(score(
            subset, {ix * config.coarse_xy, iy * config.coarse_xy, it * config.coarse_theta},
            inlier_ll));
      }
    }
  }
  Coarse c{*std::max_element(tried.begin(), tried.end(), Better), 0,
           static_cast<int>(subset.size())};
  for (const Tried& t : tried) {
    if (std::hypot(t.offset.dx - c.best.offset.dx, t.offset.dy - c.best.offset.dy) >=
        config.ambiguity_distance) {
      c.runner_up = std::max(c.runner_up, t.score.inliers);
    }
  }
  return c;
}

// The fine search: every cell, one coarse step around `start` in quarter steps, then one
// quarter step around that in twentieths (1 cm and 0.001 rad by default).
Tried Refine(const Scorer& score, const std::vector<core::Vec2>& points, const Offset& start,
             float inlier_ll, const MapRegistrationConfig& config) {
  Tried best = score(points, start, inlier_ll);
  for (const auto& [step, n] : {std::pair{0.25, 4}, std::pair{0.05, 5}}) {
    const Offset centre = best.offset;
    for (int it = -n; it <= n; ++it) {
      for (int iy = -n; iy <= n; ++iy) {
        for (int ix = -n; ix <= n; ++ix) {
          const Tried t = score(points,
                                {centre.dx + ix * step * config.coarse_xy,
                                 centre.dy + iy * step * config.coarse_xy,
                                 centre.dtheta + it * step * config.coarse_theta},
                                inlier_ll);
          if (Better(best, t)) best = t;
        }
      }
    }
  }
  return best;
}

}  // namespace

std::optional<MapRegistration> RegisterMaps(const LikelihoodField& field_A,
                                            const core::OccupancyGrid& grid_B,
                                            const core::Vec2& p_B, const core::Pose2& prior_X_AB,
                                            const MapRegistrationConfig& config) {
  const std::vector<core::Vec2> points =
      CellsNear(grid_B, p_B, config.radius, field_A.config().occupied_threshold,
                config.max_points);
  if (static_cast<int>(points.size()) < config.min_points) return std::nullopt;
  const Scorer score{field_A, prior_X_AB,
                     (prior_X_AB * core::Pose2(p_B.x(), p_B.y(), 0.0)).translation()};
  const Coarse coarse = CoarseSearch(score, points, config);
  const float inlier_ll =
      static_cast<float>(field_A.LogLikelihoodOfDistance(config.inlier_distance));
  const Tried best = Refine(score, points, coarse.best.offset, inlier_ll, config);
  MapRegistration r;
  r.X_AB = Apply(prior_X_AB, score.q_A, best.offset);
  r.inliers = best.score.inliers / static_cast<double>(points.size());
  r.runner_up = coarse.runner_up / static_cast<double>(coarse.points);
  r.points = static_cast<int>(points.size());
  const double coarse_inliers = coarse.best.score.inliers / static_cast<double>(coarse.points);
  if (r.inliers < config.min_inliers || r.runner_up > coarse_inliers - config.ambiguity_margin) {
    return std::nullopt;
  }
  return r;
}

}  // namespace retrace::nav
