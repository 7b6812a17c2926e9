#include "nav/map_registration.hpp"

#include <algorithm>
#include <cmath>
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

}  // namespace

std::optional<MapRegistration> RegisterMaps(const LikelihoodField& field_A,
                                            const core::OccupancyGrid& grid_B,
                                            const core::Vec2& p_B, const core::Pose2& prior_X_AB,
                                            const MapRegistrationConfig& config) {
  const std::vector<core::Vec2> points =
      CellsNear(grid_B, p_B, config.radius, field_A.config().occupied_threshold,
                config.max_points);
  if (static_cast<int>(points.size()) < config.min_points) return std::nullopt;
  const float inlier_ll =
      static_cast<float>(field_A.LogLikelihoodOfDistance(config.inlier_distance));
  const core::Vec2 q_A = (prior_X_AB * core::Pose2(p_B.x(), p_B.y(), 0.0)).translation();

  // Coarse: the whole window with a subset of the cells, each pose's inliers counted within a
  // distance widened by half the step's diagonal, so that the best pose of the grid is not
  // short of inliers only for lying between two steps; they are kept for the ambiguity test.
  struct Tried {
    Offset offset;
    Score score;
  };
  const std::size_t stride = (points.size() + kCoarsePoints - 1) / kCoarsePoints;
  std::vector<core::Vec2> subset;
  for (std::size_t i = 0; i < points.size(); i += stride) subset.push_back(points[i]);
  const float coarse_inlier_ll = static_cast<float>(field_A.LogLikelihoodOfDistance(
      config.inlier_distance + config.coarse_xy / std::sqrt(2.0)));
  std::vector<Tried> tried;
  const int nxy = static_cast<int>(std::floor(config.search_xy / config.coarse_xy));
  const int nth = static_cast<int>(std::floor(config.search_theta / config.coarse_theta));
  for (int it = -nth; it <= nth; ++it) {
    for (int iy = -nxy; iy <= nxy; ++iy) {
      for (int ix = -nxy; ix <= nxy; ++ix) {
        const Offset o{ix * config.coarse_xy, iy * config.coarse_xy, it * config.coarse_theta};
        tried.push_back(
            {o, ScoreOf(field_A, subset, Apply(prior_X_AB, q_A, o), coarse_inlier_ll)});
      }
    }
  }
  const auto better = [](const Tried& a, const Tried& b) {
    return a.score.log_likelihood < b.score.log_likelihood;
  };
  const Tried coarse = *std::max_element(tried.begin(), tried.end(), better);
  int runner_up = 0;
  for (const Tried& t : tried) {
    if (std::hypot(t.offset.dx - coarse.offset.dx, t.offset.dy - coarse.offset.dy) >=
        config.ambiguity_distance) {
      runner_up = std::max(runner_up, t.score.inliers);
    }
  }
  // Fine: every cell, one coarse step around the best in quarter steps, then one quarter step
  // around that in twentieths (1 cm and 0.001 rad by default).
  Tried best{coarse.offset, ScoreOf(field_A, points, Apply(prior_X_AB, q_A, coarse.offset),
                                    inlier_ll)};
  for (const double step : {0.25, 0.05}) {
    const Offset centre = best.offset;
    const int n = step == 0.25 ? 4 : 5;
    for (int it = -n; it <= n; ++it) {
      for (int iy = -n; iy <= n; ++iy) {
        for (int ix = -n; ix <= n; ++ix) {
          const Offset o{centre.dx + ix * step * config.coarse_xy,
                         centre.dy + iy * step * config.coarse_xy,
                         centre.dtheta + it * step * config.coarse_theta};
          const Tried t{o, ScoreOf(field_A, points, Apply(prior_X_AB, q_A, o), inlier_ll)};
          if (better(best, t)) best = t;
        }
      }
    }
  }
  const double n = static_cast<double>(points.size());
  const double n_coarse = static_cast<double>(subset.size());
  MapRegistration r;
  r.X_AB = Apply(prior_X_AB, q_A, best.offset);
  r.inliers = best.score.inliers / n;
  r.runner_up = runner_up / n_coarse;
  r.points = static_cast<int>(points.size());
  if (r.inliers < config.min_inliers ||
      r.runner_up > coarse.score.inliers / n_coarse - config.ambiguity_margin) {
    return std::nullopt;
  }
  return r;
}
}  // namespace retrace::nav
