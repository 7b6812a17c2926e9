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
  core::Vec2 dir = core::Vec2::Zero();  // unit vector of the beam in M
  double z = 0.0;                       // m, the reading (hits)
  double length = 0.0;                  // m, how far to cast
  double clear_to = 0.0;                // m, clearing beams: cells with t_out <= clear_to are free
};

BeamPlan PlanBeam(const MapperConfig& config, double hit_range_max, const core::LaserScan& scan,
                  std::size_t i) {
  BeamPlan plan;
  if (scan.NoReturn(i)) {
    // Nothing within the LiDAR's own range: free space is known up to that range at most (a
    // 5 m LiDAR says nothing about 5 to 10 m).
    plan.clear_to = std::min(config.no_return_range, scan.range_max);
    if (!(plan.clear_to > 0.0)) return plan;
    plan.kind = BeamKind::kClear;
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

// The plans of all beams of `scan`, taken from X_ML, with their directions in M; widens
// [*lo, *hi] (M) to every planned beam's far end.
std::vector<BeamPlan> PlanBeams(const MapperConfig& config, double hit_range_max,
                                const core::LaserScan& scan, const core::Pose2& X_ML,
                                core::Vec2* lo, core::Vec2* hi) {
  const core::Vec2 p_ML = X_ML.translation();
  std::vector<BeamPlan> plans(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    plans[i] = PlanBeam(config, hit_range_max, scan, i);
    if (plans[i].kind == BeamKind::kSkip) continue;
    const double a = X_ML.theta + scan.Angle(i);
    plans[i].dir = core::Vec2(std::cos(a), std::sin(a));
    const core::Vec2 end = p_ML + plans[i].length * plans[i].dir;
    *lo = lo->cwiseMin(end);
    *hi = hi->cwiseMax(end);
  }
  return plans;
}

// Exact cell traversal (Amanatides & Woo 1987) of the ray from `start` along the unit vector
// `dir` from t0 to `length` metres: calls visit(cell, t_in, t_out) for every cell whose
// interior the ray crosses beyond t0, in order, with the ray's stretch [t_in, t_out] (m from
// start) inside it (t_in is t0 in the first cell; t_out is the cell's true exit, which may
// exceed `length`). visit returns false to stop.
template <class Visit>
void TraverseCells(const core::OccupancyGrid& grid, const core::Vec2& start, const core::Vec2& dir,
                   double t0, double length, Visit&& visit) {
  const double res = grid.resolution();
  const core::Vec2 from = t0 > 0.0 ? core::Vec2(start + t0 * dir) : start;
  const double gx = (from.x() - grid.origin().x()) / res;
  const double gy = (from.y() - grid.origin().y()) / res;
  core::CellIndex c{static_cast<int>(std::floor(gx)), static_cast<int>(std::floor(gy))};
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const int step_x = dir.x() > 0.0 ? 1 : -1;
  const int step_y = dir.y() > 0.0 ? 1 : -1;
  const double delta_x = dir.x() != 0.0 ? res / std::abs(dir.x()) : kInf;
  const double delta_y = dir.y() != 0.0 ? res / std::abs(dir.y()) : kInf;
  double next_x = dir.x() > 0.0   ? t0 + (c.x + 1 - gx) * delta_x
                  : dir.x() < 0.0 ? t0 + (gx - c.x) * delta_x
                                  : kInf;
  double next_y = dir.y() > 0.0   ? t0 + (c.y + 1 - gy) * delta_y
                  : dir.y() < 0.0 ? t0 + (gy - c.y) * delta_y
                                  : kInf;
  // The cells crossed lie in the bounding box of the first and the last one, which the grid
  // holds (Integrate grows it to every beam's far end first).
  const core::Vec2 to = start + length * dir;
  RETRACE_CHECK(grid.Contains(c) &&
                grid.Contains({static_cast<int>(std::floor((to.x() - grid.origin().x()) / res)),
                               static_cast<int>(std::floor((to.y() - grid.origin().y()) / res))}));
  double t_in = t0;
  // A ray of length L crosses at most L/res + 1 columns and as many rows.
  const long max_steps = 2 * static_cast<long>(std::ceil((length - t0) / res)) + 4;
  for (long step = 0; step < max_steps && t_in < length; ++step) {
    const double t_out = std::min(next_x, next_y);
    if (t_out > t_in) {  // skip the zero-length stretch of a corner crossing
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

// Near the LiDAR its beams lie closer together than cells, and every cell their free stretches
// cross is crossed by many of them. Beam i's free stretch is traced only from where the beams of
// a higher level (more trailing zero bits in their index: every 2nd, 4th, ... beam) lie more
// than `spacing` apart: at range r the beams of level >= m are 2^m · increment · r apart, so
// beam i of level l is needed from spacing / (2^(l+1) · increment) on. Beams of level
// kDenseLevels and above are traced from the LiDAR.
constexpr int kDenseLevels = 8;
double FreeStretchStart(std::size_t i, double increment, double spacing) {
  int level = 0;
  while (level < kDenseLevels && ((i >> level) & 1U) == 0) ++level;
  if (level >= kDenseLevels || !(increment > 0.0)) return 0.0;
  return spacing / std::ldexp(increment, level + 1);
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

inline bool Mapper::Marked(const std::vector<std::uint64_t>& bits, std::size_t i) {
  return (bits[i >> 6] >> (i & 63)) & 1U;
}

inline void Mapper::ProposeFree(std::size_t i) {
  std::uint64_t& word = touched_bits_[i >> 6];
  const std::uint64_t bit = std::uint64_t{1} << (i & 63);
  if ((word & bit) != 0) return;
  word |= bit;
  touched_.push_back(i);
}

inline void Mapper::ProposeNearEnd(std::size_t i, float delta, bool end_cell) {
  ProposeFree(i);
  std::uint64_t& word = near_bits_[i >> 6];
  const std::uint64_t bit = std::uint64_t{1} << (i & 63);
  Proposal& p = proposals_[i];
  if ((word & bit) == 0) {
    word |= bit;
    p = Proposal{};
  }
  p.sum += delta;
  ++p.count;
  p.end_cell |= end_cell ? 1 : 0;
}

void Mapper::GrowFor(const core::Vec2& lo, const core::Vec2& hi) {
  grid_.GrowToInclude(lo, kGrowMargin);
  grid_.GrowToInclude(hi, kGrowMargin);
  // The scratch: every bit is clear between scans (each scan clears the bits it set), a grown
  // grid only needs longer bitmaps; proposals are valid where the near bit is set.
  const std::size_t cells = grid_.log_odds().size();
  if (proposals_.size() < cells) {
    proposals_.resize(cells);
    touched_bits_.resize((cells + 63) / 64);
    near_bits_.resize((cells + 63) / 64);
  }
  touched_.clear();
}

inline void Mapper::ProposeHitBeam(const core::Vec2& p_ML, const core::Vec2& dir, double z,
                                   double free_from, double length, double reach, float hit) {
  const double near_end = z - reach;
  TraverseCells(grid_, p_ML, dir, free_from, length,
                [&](core::CellIndex c, double t_in, double t_out) {
                  if (t_out < near_end) {
                    ProposeFree(grid_.Index(c));
                    return true;
                  }
                  const double d = SignedDistanceToEndPoint(t_in, t_out, z);
                  if (d > reach) return false;
                  const float delta =
                      d == 0.0 ? hit : static_cast<float>(LogOddsUpdate(config_.inverse_model, d));
                  if (delta != 0.0f) ProposeNearEnd(grid_.Index(c), delta, d == 0.0);
                  return true;
                });
}

inline void Mapper::ProposeClearBeam(const core::Vec2& p_ML, const core::Vec2& dir, double length,
                                     double clear_to) {
  // It clears only up to the first cell that the map already holds as occupied or that this
  // scan's hits mark, so that dropouts neither wear walls away nor paint free space behind them
  // (a wall first seen in this scan included).
  const std::vector<float>& before = grid_.log_odds();
  const auto blocks = [&](std::size_t cell) {
    return before[cell] > 0.0f || (Marked(near_bits_, cell) && proposals_[cell].end_cell != 0);
  };
  TraverseCells(grid_, p_ML, dir, 0.0, length,
                [&](core::CellIndex c, double /*t_in*/, double t_out) {
                  const std::size_t cell = grid_.Index(c);
                  if (t_out > clear_to || blocks(cell)) return false;
                  ProposeFree(cell);
                  return true;
                });
}

void Mapper::ApplyProposals(float hit, float miss) {
  std::vector<float>& log_odds = grid_.log_odds();
  const auto l_min = static_cast<float>(config_.log_odds_min);
  const auto l_max = static_cast<float>(config_.log_odds_max);
  for (const std::size_t i : touched_) {
    // One update per cell and scan: the beams of one scan that meet a cell are not independent
    // measurements of it. A cell holding an end point takes the hit (hits win over beams that
    // graze it); a cell near end points the mean of those beams' inverse-model values (they
    // win over beams that only pass through); any other cell the miss.
    float delta = miss;
    const std::uint64_t bit = std::uint64_t{1} << (i & 63);
    if ((near_bits_[i >> 6] & bit) != 0) {
      const Proposal& p = proposals_[i];
      delta = p.end_cell != 0 ? hit : p.sum / static_cast<float>(p.count);
      near_bits_[i >> 6] &= ~bit;
    }
    touched_bits_[i >> 6] &= ~bit;
    log_odds[i] = std::clamp(log_odds[i] + delta, l_min, l_max);  // eq. (4)
  }
}

void Mapper::Integrate(const core::LaserScan& scan, const core::Pose2& X_MR) {
  RETRACE_CHECK(std::isfinite(X_MR.x) && std::isfinite(X_MR.y) && std::isfinite(X_MR.theta));
  const core::Pose2 X_ML = X_MR * robot_.X_RL;
  const core::Vec2 p_ML = X_ML.translation();
  core::Vec2 lo = p_ML;
  core::Vec2 hi = p_ML;
  const std::vector<BeamPlan> plans = PlanBeams(config_, robot_.range_max, scan, X_ML, &lo, &hi);
  // Grow before any index is taken: growing shifts the indices of existing cells.
  GrowFor(lo, hi);

  const auto hit = static_cast<float>(HitLogOdds(config_.inverse_model));
  const auto miss = static_cast<float>(MissLogOdds(config_.inverse_model));
  const double reach = config_.inverse_model.ReachBehind();
  const double spacing = 0.5 * config_.resolution;
  MapperStats stats;
  stats.keyframes = stats_.keyframes + 1;
  // Hits first, then the clearing beams, so that these stop at this scan's end points too.
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const BeamPlan& plan = plans[i];
    if (plan.kind == BeamKind::kSkip) ++stats.beams_skipped;
    if (plan.kind != BeamKind::kHit) continue;
    ++stats.beams_hit;
    // The free stretch, well before the end point, from where this beam is needed; then the
    // end point's neighbourhood, every cell of it.
    const double free_from =
        std::min(FreeStretchStart(i, scan.angle_increment, spacing), std::max(plan.z - reach, 0.0));
    ProposeHitBeam(p_ML, plan.dir, plan.z, free_from, plan.length, reach, hit);
  }
  // A beam without a usable return cannot tell open space from a dropout on a wall. Within
  // no_return_range the beams lie at most a cell apart (0.25 deg at 10 m: 4.4 cm), so of a run
  // of clearing beams every other one is enough; each traced one stops at its own blocking cell.
  const auto clearing = [&](std::size_t j) {
    return j < plans.size() && plans[j].kind == BeamKind::kClear;
  };
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const BeamPlan& plan = plans[i];
    if (plan.kind != BeamKind::kClear) continue;
    ++stats.beams_cleared;
    if ((i & 1U) != 0 && i > 0 && clearing(i - 1) && clearing(i + 1) &&
        plan.clear_to * scan.angle_increment <= spacing * 2.0) {
      continue;
    }
    ProposeClearBeam(p_ML, plan.dir, plan.length, plan.clear_to);
  }
  ApplyProposals(hit, miss);
  stats.cells_updated = touched_.size();
  stats_ = stats;
}

}  // namespace retrace::nav
