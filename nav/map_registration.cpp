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

  // Coarse: the whole window; every pose's inlier count is kept for the ambiguity test.
  struct Tried {
    Offset offset;
    Score score;
  };
  std::vector<Tried> tried;
  const int nxy = static_cast<int>(std::floor(config.search_xy / config.coarse_xy));
  const int nth = static_cast<int>(std::floor(config.search_theta / config.coarse_theta));
  for (int it = -nth; it <= nth; ++it) {
    for (int iy = -nxy; iy <= nxy; ++iy) {
      for (int ix = -nxy; ix <= nxy; ++ix) {
        const Offset o{ix * config.coarse_xy, iy * config.coarse_xy, it * config.coarse_theta};
        tried.push_back({o, ScoreOf(field_A, points, Apply(prior_X_AB, q_A, o), inlier_ll)});
      }
    }
  }
  const auto better = [](const Tried& a, const Tried& b) {
    return a.score.log_likelihood < b.score.log_likelihood;
  };
  Tried best = *std::max_element(tried.begin(), tried.end(), better);
  int runner_up = 0;
  for (const Tried& t : tried) {
    if (std::hypot(t.offset.dx - best.offset.dx, t.offset.dy - best.offset.dy) >=
        config.ambiguity_distance) {
      runner_up = std::max(runner_up, t.score.inliers);
    }
  }
  // Fine: a fifth of the coarse steps, one coarse step around the best.
  const Offset centre = best.offset;
  for (int it = -5; it <= 5; ++it) {
    for (int iy = -5; iy <= 5; ++iy) {
      for (int ix = -5; ix <= 5; ++ix) {
        const Offset o{centre.dx + ix * config.coarse_xy / 5.0,
                       centre.dy + iy * config.coarse_xy / 5.0,
                       centre.dtheta + it * config.coarse_theta / 5.0};
        const Tried t{o, ScoreOf(field_A, points, Apply(prior_X_AB, q_A, o), inlier_ll)};
        if (better(best, t)) best = t;
      }
    }
  }
  const double n = static_cast<double>(points.size());
  MapRegistration r;
  r.X_AB = Apply(prior_X_AB, q_A, best.offset);
  r.inliers = best.score.inliers / n;
  r.runner_up = runner_up / n;
  r.points = static_cast<int>(points.size());
  if (r.inliers < config.min_inliers || r.runner_up > r.inliers - config.ambiguity_margin) {
    return std::nullopt;
  }
  return r;
}
}  // namespace retrace::nav
