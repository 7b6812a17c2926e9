#include "nav/place_search.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace retrace::nav {
namespace {

// The best heading's score at each searched position.
struct PositionScore {
  double score;
  double x, y, theta;
};

// Scores every position of the grid at one heading; keeps each position's best.
void ScoreHeading(const LikelihoodField& field, const core::Pose2& X_RL,
                  const std::vector<double>& xs_L, const std::vector<double>& ys_L,
                  const core::Pose2& prior, double theta, int half, double step,
                  std::vector<PositionScore>* best) {
  const core::Pose2 X_MR0(0.0, 0.0, theta);
  const core::Pose2 X_ML0 = X_MR0 * X_RL;  // the LiDAR at the robot's position 0
  std::vector<core::Vec2> p(xs_L.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = X_ML0 * core::Vec2(xs_L[i], ys_L[i]);
  const int side = 2 * half + 1;
  for (int iy = 0; iy < side; ++iy) {
    const double y = prior.y + (iy - half) * step;
    for (int ix = 0; ix < side; ++ix) {
      const double x = prior.x + (ix - half) * step;
      double sum = 0.0;
      for (const core::Vec2& q : p) sum += field.LogLikelihood(core::Vec2(x + q.x(), y + q.y()));
      PositionScore& b = (*best)[static_cast<std::size_t>(iy * side + ix)];
      if (sum > b.score) b = {sum, x, y, theta};
    }
  }
}

}  // namespace

void ScanEndPoints(const core::LaserScan& scan, const RobotGeometry& robot, int beam_step,
                   std::vector<double>* xs_L, std::vector<double>* ys_L) {
  xs_L->clear();
  ys_L->clear();
  const std::size_t step = static_cast<std::size_t>(std::max(1, beam_step));
  for (std::size_t i = 0; i < scan.size(); i += step) {
    const double r = scan.ranges[i];
    if (!scan.Valid(i) || r < robot.range_min || r > robot.range_max) continue;
    xs_L->push_back(r * std::cos(scan.Angle(i)));
    ys_L->push_back(r * std::sin(scan.Angle(i)));
  }
}

std::vector<ScoredPlace> SearchPlaces(const LikelihoodField& field, const RobotGeometry& robot,
                                      const std::vector<double>& xs_L,
                                      const std::vector<double>& ys_L, const core::Pose2& prior,
                                      double radius_xy, double radius_theta,
                                      const PlaceSearchConfig& config) {
  if (xs_L.empty()) return {};
  const int half = static_cast<int>(std::ceil(radius_xy / config.step_xy));
  const int half_theta = static_cast<int>(std::ceil(radius_theta / config.step_theta));
  const std::size_t side = static_cast<std::size_t>(2 * half + 1);
  std::vector<PositionScore> best(side * side, {-INFINITY, 0.0, 0.0, 0.0});
  for (int it = -half_theta; it <= half_theta; ++it) {
    ScoreHeading(field, robot.X_RL, xs_L, ys_L, prior, prior.theta + it * config.step_theta, half,
                 config.step_xy, &best);
  }
  std::sort(best.begin(), best.end(),
            [](const PositionScore& a, const PositionScore& b) { return a.score > b.score; });
  std::vector<ScoredPlace> places;
  for (const PositionScore& c : best) {
    if (static_cast<int>(places.size()) >= config.max_places ||
        c.score < best.front().score - config.margin) {
      break;
    }
    const core::Pose2 X_MR(c.x, c.y, c.theta);
    const bool apart = std::all_of(places.begin(), places.end(), [&](const ScoredPlace& p) {
      return core::Distance(p.X_MR, X_MR) >= config.min_separation;
    });
    if (apart) places.push_back({X_MR, c.score});
  }
  return places;
}

std::vector<Particle> ParticlesAtPlaces(const std::vector<ScoredPlace>& places, int count,
                                        double sigma_xy, double sigma_theta, core::Rng& rng) {
  std::vector<Particle> out;
  if (places.empty() || count <= 0) return out;
  out.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const core::Pose2& c = places[static_cast<std::size_t>(i) % places.size()].X_MR;
    out.push_back({core::Pose2(c.x + sigma_xy * rng.Normal(), c.y + sigma_xy * rng.Normal(),
                               c.theta + sigma_theta * rng.Normal()),
                   1.0 / count});
  }
  return out;
}

}  // namespace retrace::nav
