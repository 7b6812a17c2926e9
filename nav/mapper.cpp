#include "nav/mapper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/angle.hpp"
#include "core/check.hpp"
#include "core/errors.hpp"

namespace retrace::nav {
namespace {

// Cells of margin kept around everything a scan touches when the grid grows.
constexpr int kGrowMargin = 2;

enum class BeamKind { kSkip, kHit, kClear };

// How one beam is used: a hit at range z (cast on to z + reach), or free space only up to
// clear_to (cells lying wholly inside it), or not at all.
struct BeamPlan {
  BeamKind kind = BeamKind::kSkip;
  double z = 0.0;         // m, the reading (hits)
  double length = 0.0;    // m, how far to cast
  double clear_to = 0.0;  // m, clearing beams: cells with t_out <= clear_to are free
};

BeamPlan PlanBeam(const MapperConfig& config, double hit_range_max, const core::LaserScan& scan,
                  std::size_t i) {
  BeamPlan plan;
  if (scan.NoReturn(i)) {
    if (config.no_return_range <= 0.0) return plan;
    plan.kind = BeamKind::kClear;
    plan.clear_to = config.no_return_range;
    plan.length = plan.clear_to;
    return plan;
  }
  if (!scan.Valid(i)) return plan;  // NaN, -inf, or outside [range_min, range_max]
  const double z = scan.ranges[i];
  if (z <= hit_range_max) {
    plan.kind = BeamKind::kHit;
    plan.z = z;
    plan.length = z + config.inverse_model.ReachBehind();
    return plan;
  }
  // A real return too far away to mark: the space before it is free, but keep clear of the
  // end point's neighbourhood, and of no_return_range like a no-return beam.
  plan.clear_to = std::min(z - config.inverse_model.ReachBehind(), config.no_return_range);
  if (plan.clear_to <= 0.0) return plan;
  plan.kind = BeamKind::kClear;
  plan.length = plan.clear_to;
  return plan;
}

// Exact cell traversal (Amanatides & Woo 1987) of the ray from `start` along the unit vector
// `dir` for `length` metres: calls visit(cell, t_in, t_out) for every cell whose interior the
// ray crosses, in order, with the ray's stretch [t_in, t_out] (m from start) inside it
// (t_out is the cell's true exit, which may exceed `length`). visit returns false to stop.
template <class Visit>
void TraverseCells(const core::OccupancyGrid& grid, const core::Vec2& start, const core::Vec2& dir,
                   double length, Visit&& visit) {
  const double res = grid.resolution();
  const double gx = (start.x() - grid.origin().x()) / res;
  const double gy = (start.y() - grid.origin().y()) / res;
  core::CellIndex c{static_cast<int>(std::floor(gx)), static_cast<int>(std::floor(gy))};
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const int step_x = dir.x() > 0.0 ? 1 : -1;
  const int step_y = dir.y() > 0.0 ? 1 : -1;
  const double delta_x = dir.x() != 0.0 ? res / std::abs(dir.x()) : kInf;
  const double delta_y = dir.y() != 0.0 ? res / std::abs(dir.y()) : kInf;
  double next_x = dir.x() > 0.0   ? (c.x + 1 - gx) * delta_x
                  : dir.x() < 0.0 ? (gx - c.x) * delta_x
                                  : kInf;
  double next_y = dir.y() > 0.0   ? (c.y + 1 - gy) * delta_y
                  : dir.y() < 0.0 ? (gy - c.y) * delta_y
                                  : kInf;
  double t_in = 0.0;
  // A ray of length L crosses at most L/res + 1 columns and as many rows.
  const long max_steps = 2 * static_cast<long>(std::ceil(length / res)) + 4;
  for (long step = 0; step < max_steps && t_in < length; ++step) {
    const double t_out = std::min(next_x, next_y);
    if (t_out > t_in) {  // skip the zero-length stretch of a corner crossing
      RETRACE_CHECK(grid.Contains(c));
      if (!visit(c, t_in, t_out)) return;
    }
    t_in = t_out;
    if (next_x < next_y) {
      c.x += step_x;
      next_x += delta_x;
    } else {
      c.y += step_y;
      next_y += delta_y;
    }
  }
}

void RequireConfig(bool ok, const char* key, const std::string& message) {
  if (!ok) throw core::ConfigError(key, message);
}

}  // namespace

void MapperConfig::Validate() const {
  core::RequirePositive("resolution", resolution);
  core::RequirePositive("initial_size", initial_size);
  core::RequireNonNegative("keyframe_distance", keyframe_distance);
  core::RequireInRange("keyframe_angle_deg", keyframe_angle_deg, 0.0, 180.0);
  RequireConfig(log_odds_min < 0.0 && std::isfinite(log_odds_min), "log_odds_min",
                "must be a finite number < 0, got " + core::FormatNumber(log_odds_min));
  RequireConfig(log_odds_max > 0.0 && std::isfinite(log_odds_max), "log_odds_max",
                "must be a finite number > 0, got " + core::FormatNumber(log_odds_max));
  core::RequireNonNegative("no_return_range", no_return_range);
  try {
    inverse_model.Validate();
  } catch (const core::ConfigError& e) {
    throw core::ConfigError("inverse_model." + e.key_path(), e.detail());
  }
}

Mapper::Mapper(const MapperConfig& config, const RobotGeometry& robot)
    : config_(config), robot_(robot) {
  config_.Validate();
  robot_.Validate();
  const int half = static_cast<int>(std::ceil(0.5 * config_.initial_size / config_.resolution));
  grid_ = core::OccupancyGrid(2 * half, 2 * half, config_.resolution,
                              core::Vec2(-half * config_.resolution, -half * config_.resolution));
}

bool Mapper::KeyframeDue() const {
  if (path_.empty()) return true;
  const core::Pose2& last = path_.back();
  return core::Distance(last, X_MR_) >= config_.keyframe_distance ||
         std::abs(core::AngleDiff(X_MR_.theta, last.theta)) >=
             core::DegToRad(config_.keyframe_angle_deg);
}

bool Mapper::OnScan(const core::LaserScan& scan) {
  if (!KeyframeDue()) return false;
  Integrate(scan, X_MR_);
  path_.PushBack(X_MR_);
  return true;
}

void Mapper::ProposeUpdate(core::CellIndex c, float delta, bool end_cell) {
  const std::size_t i = grid_.Index(c);
  Proposal& p = proposals_[i];
  if (p.stamp != scan_id_) {
    p = {scan_id_, 0.0f, 0, 0};
    touched_.push_back(i);
  }
  p.sum += delta;
  ++p.count;
  p.end_cell |= end_cell ? 1 : 0;
}

void Mapper::Integrate(const core::LaserScan& scan, const core::Pose2& X_MR) {
  RETRACE_CHECK(std::isfinite(X_MR.x) && std::isfinite(X_MR.y) && std::isfinite(X_MR.theta));
  const core::Pose2 X_ML = X_MR * robot_.X_RL;
  const core::Vec2 p_ML = X_ML.translation();

  std::vector<BeamPlan> plans(scan.size());
  core::Vec2 lo = p_ML;
  core::Vec2 hi = p_ML;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    plans[i] = PlanBeam(config_, robot_.range_max, scan, i);
    if (plans[i].kind == BeamKind::kSkip) continue;
    const double a = X_ML.theta + scan.Angle(i);
    const core::Vec2 end = p_ML + plans[i].length * core::Vec2(std::cos(a), std::sin(a));
    lo = lo.cwiseMin(end);
    hi = hi.cwiseMax(end);
  }
  // Grow before any index is taken: growing shifts the indices of existing cells.
  grid_.GrowToInclude(lo, kGrowMargin);
  grid_.GrowToInclude(hi, kGrowMargin);
  const std::size_t cells = grid_.log_odds().size();
  // A grown grid shifts every cell's index, but entries stamped by an earlier scan are stale
  // wherever they land, so the scratch only needs to be long enough; it is cleared only when
  // the stamp would wrap.
  if (scan_id_ == std::numeric_limits<std::uint32_t>::max()) {
    proposals_.assign(cells, Proposal{});
    scan_id_ = 0;
  } else if (proposals_.size() < cells) {
    proposals_.resize(cells);
  }
  ++scan_id_;
  touched_.clear();

  const auto hit = static_cast<float>(HitLogOdds(config_.inverse_model));
  const auto miss = static_cast<float>(MissLogOdds(config_.inverse_model));
  MapperStats stats;
  stats.keyframes = stats_.keyframes + 1;
  // Hits first, then the clearing beams, so that these stop at this scan's end points too.
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const BeamPlan& plan = plans[i];
    if (plan.kind == BeamKind::kSkip) ++stats.beams_skipped;
    if (plan.kind != BeamKind::kHit) continue;
    ++stats.beams_hit;
    const double a = X_ML.theta + scan.Angle(i);
    TraverseCells(grid_, p_ML, core::Vec2(std::cos(a), std::sin(a)), plan.length,
                  [&](core::CellIndex c, double t_in, double t_out) {
                    const double d = SignedDistanceToEndPoint(t_in, t_out, plan.z);
                    if (d > config_.inverse_model.ReachBehind()) return false;
                    // Exact constants away from the end point; the model's curve near it.
                    const float delta =
                        d < -config_.inverse_model.ReachBehind() ? miss
                        : d == 0.0                               ? hit
                                   : static_cast<float>(LogOddsUpdate(config_.inverse_model, d));
                    if (delta != 0.0f) ProposeUpdate(c, delta, d == 0.0);
                    return true;
                  });
  }
  // A beam without a usable return cannot tell open space from a dropout on a wall: it clears
  // only up to the first cell that the map already holds as occupied or that this scan's hits
  // mark, so that dropouts neither wear walls away nor paint free space behind them (a wall
  // first seen in this scan included).
  const std::vector<float>& before = grid_.log_odds();
  const auto blocks = [&](std::size_t cell) {
    const Proposal& p = proposals_[cell];
    return before[cell] > 0.0f || (p.stamp == scan_id_ && p.end_cell != 0);
  };
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const BeamPlan& plan = plans[i];
    if (plan.kind != BeamKind::kClear) continue;
    ++stats.beams_cleared;
    const double a = X_ML.theta + scan.Angle(i);
    TraverseCells(grid_, p_ML, core::Vec2(std::cos(a), std::sin(a)), plan.length,
                  [&](core::CellIndex c, double /*t_in*/, double t_out) {
                    if (t_out > plan.clear_to || blocks(grid_.Index(c))) return false;
                    ProposeUpdate(c, miss, false);
                    return true;
                  });
  }

  std::vector<float>& log_odds = grid_.log_odds();
  const auto l_min = static_cast<float>(config_.log_odds_min);
  const auto l_max = static_cast<float>(config_.log_odds_max);
  for (const std::size_t i : touched_) {
    // One update per cell and scan: the beams of one scan that meet a cell are not independent
    // measurements of it. A cell holding an end point takes the hit (hits win over beams that
    // graze it); any other cell takes the mean of its beams' inverse-model values.
    const Proposal& p = proposals_[i];
    const float delta = p.end_cell != 0 ? hit : p.sum / static_cast<float>(p.count);
    log_odds[i] = std::clamp(log_odds[i] + delta, l_min, l_max);  // eq. (4)
  }
  stats.cells_updated = touched_.size();
  stats_ = stats;
}

}  // namespace retrace::nav
