#include "nav/beam_evidence.hpp"

#include <cmath>

#include "core/check.hpp"

namespace retrace::nav {
namespace {

double Share(int n, int total) {
  return total > 0 ? static_cast<double>(n) / static_cast<double>(total) : 0.0;
}

// m before a wall where its normal is taken, and cos 20°: a ray that meets a wall at less than
// 20° only grazes it (a corner cell on its way, the estimate a few centimetres off), which says
// nothing of the pose; one that meets it more squarely passes through it.
constexpr double kBack = 0.1;
constexpr double kMinIncidence = 0.34;

// Whether a ray along dir meets the wall ahead of point p (in free space just before it) at
// more than 20° from the wall's surface: the distance field's gradient at p is the wall's normal.
bool HeadOn(const LikelihoodField& field, const core::Vec2& p, const core::Vec2& dir) {
  constexpr double h = 0.05;
  const core::Vec2 dx(h, 0.0), dy(0.0, h);
  const core::Vec2 g(field.DistanceAt(p + dx) - field.DistanceAt(p - dx),
                     field.DistanceAt(p + dy) - field.DistanceAt(p - dy));
  const double norm = g.norm();
  if (!(norm > 1e-9)) return true;  // no gradient (a one-cell wall): count it
  return std::abs(g.dot(dir)) / norm >= kMinIncidence;
}

}  // namespace

double BeamEvidence::Coverage() const { return Share(total() - unknown, total()); }
double BeamEvidence::Explained() const { return Share(explained, total()); }
double BeamEvidence::Contradicted() const { return Share(through_wall, total()); }

BeamEvidenceThresholds BeamEvidenceThresholds::Of(const LikelihoodField& field) {
  const double sigma = field.config().sigma_hit;
  return {1.5 * sigma, 2.0 * sigma};
}

void ClassifyEachBeam(const LikelihoodField& field, const GridRayCaster& caster,
                      const core::Pose2& X_ML, std::span<const double> xs_L,
                      std::span<const double> ys_L, std::vector<BeamClass>* classes) {
  RETRACE_CHECK(xs_L.size() == ys_L.size());
  const BeamEvidenceThresholds t = BeamEvidenceThresholds::Of(field);
  const core::Vec2 origin = X_ML.translation();
  const double c = std::cos(X_ML.theta), s = std::sin(X_ML.theta);
  classes->assign(xs_L.size(), BeamClass::kShorter);
  for (std::size_t i = 0; i < xs_L.size(); ++i) {
    const double range = std::hypot(xs_L[i], ys_L[i]);
    if (!(range > 0.0)) continue;
    const core::Vec2 end(origin.x() + c * xs_L[i] - s * ys_L[i],
                         origin.y() + s * xs_L[i] + c * ys_L[i]);
    BeamClass& k = (*classes)[i];
    // A wall of the map on the ray, short of the end point: the beam saw through it, whatever
    // it ends on.
    const core::Vec2 dir = (end - origin) / range;
    const double hit = caster.Cast(origin, dir, range);
    if (hit < range - t.contradiction_margin && HeadOn(field, origin + (hit - kBack) * dir, dir)) {
      k = BeamClass::kThroughWall;
    } else if (field.DistanceAt(end) <= t.explained_distance) {
      k = BeamClass::kExplained;
    } else if (!field.Known(end)) {
      k = BeamClass::kUnknown;
    }
  }
}

BeamEvidence CountClasses(std::span<const BeamClass> classes) {
  BeamEvidence e;
  for (const BeamClass k : classes) {
    switch (k) {
      case BeamClass::kExplained: ++e.explained; break;
      case BeamClass::kShorter: ++e.shorter; break;
      case BeamClass::kUnknown: ++e.unknown; break;
      case BeamClass::kThroughWall: ++e.through_wall; break;
    }
  }
  return e;
}

BeamEvidence ClassifyBeams(const LikelihoodField& field, const GridRayCaster& caster,
                           const core::Pose2& X_ML, std::span<const double> xs_L,
                           std::span<const double> ys_L) {
  std::vector<BeamClass> classes;
  ClassifyEachBeam(field, caster, X_ML, xs_L, ys_L, &classes);
  return CountClasses(classes);
}

double GridCoverage(const core::OccupancyGrid& grid, const core::Pose2& X_ML,
                    std::span<const double> xs_L, std::span<const double> ys_L) {
  RETRACE_CHECK(xs_L.size() == ys_L.size());
  if (xs_L.empty() || grid.empty()) return 0.0;
  const double known = core::Logit(kKnownProbability);
  int covered = 0;
  for (std::size_t i = 0; i < xs_L.size(); ++i) {
    const core::Vec2 end = (X_ML * core::Pose2(xs_L[i], ys_L[i], 0.0)).translation();
    const core::CellIndex cell = grid.WorldToCell(end);
    if (grid.Contains(cell) && std::abs(static_cast<double>(grid.LogOdds(cell))) >= known) {
      ++covered;
    }
  }
  return static_cast<double>(covered) / static_cast<double>(xs_L.size());
}

}  // namespace retrace::nav
