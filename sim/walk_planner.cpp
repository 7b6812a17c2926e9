#include "sim/walk_planner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <queue>
#include <string>
#include <utility>

#include "core/check.hpp"
#include "core/errors.hpp"
#include "core/segment.hpp"

namespace retrace::sim {
namespace {

constexpr std::int64_t kMaxCells = 8'000'000;
constexpr double kMaxCellSize = 0.5;  // m: coarser cells would close the doors of a building
constexpr double kSqrt2 = 1.4142135623730951;

struct Neighbour {
  int dx;
  int dy;
  double cost;
};
// Orthogonal moves first: diagonal moves test their two orthogonal cells (no corner cutting).
constexpr Neighbour kNeighbours[8] = {{1, 0, 1.0},     {-1, 0, 1.0},    {0, 1, 1.0},
                                      {0, -1, 1.0},    {1, 1, kSqrt2},  {-1, 1, kSqrt2},
                                      {1, -1, kSqrt2}, {-1, -1, kSqrt2}};

}  // namespace

void WalkPlannerConfig::Validate() const {
  core::RequireInRange("cell_size", cell_size, 0.02, 2.0);
  core::RequireNonNegative("margin", margin);
  core::RequireNonNegative("area_padding", area_padding);
}

double PlanningCellSize(const Aabb& area, const WalkPlannerConfig& config) {
  config.Validate();
  const Vec2 extent = area.max - area.min;
  double cell = config.cell_size;
  // The configured cell, or the first one coarser by whole centimetres that fits the limit.
  auto cells = [&extent](double c) {
    return std::ceil(extent.x() / c) * std::ceil(extent.y() / c);
  };
  if (extent.allFinite() && cells(cell) > static_cast<double>(kMaxCells)) {
    cell = std::ceil(100.0 * std::sqrt(extent.x() * extent.y() / kMaxCells)) / 100.0;
    while (cells(cell) > static_cast<double>(kMaxCells)) cell += 0.01;
  }
  return cell;
}

WalkPlanner::WalkPlanner(const GeometryIndex& index, const Aabb& area, double pedestrian_radius,
                         const WalkPlannerConfig& config)
    : cell_(PlanningCellSize(area, config)),
      inflation_(pedestrian_radius + config.margin),
      origin_(area.min) {
  config.Validate();
  RETRACE_CHECK(pedestrian_radius > 0.0);
  const Vec2 extent = area.max - area.min;
  if (!extent.allFinite() || !(extent.x() > 0.0) || !(extent.y() > 0.0)) {
    throw core::WorldError("pedestrian planning area is empty");
  }
  if (cell_ > kMaxCellSize) {
    char buf[200];
    std::snprintf(buf, sizeof(buf),
                  "pedestrian planning area %.0f m x %.0f m needs cells of %.2f m to fit %lld "
                  "cells (at most %.1f m resolve a door); use smaller pedestrian regions",
                  extent.x(), extent.y(), cell_, static_cast<long long>(kMaxCells), kMaxCellSize);
    throw core::WorldError(buf);
  }
  const double cells_x = std::ceil(extent.x() / cell_);
  const double cells_y = std::ceil(extent.y() / cell_);
  nx_ = std::max(1, static_cast<int>(cells_x));
  ny_ = std::max(1, static_cast<int>(cells_y));

  // Cells near a boundary are blocked. The remaining ("far") cells are each entirely inside or
  // outside the solids; when the inflation radius exceeds half a cell diagonal, a segment
  // between two neighbouring far centres cannot cross a boundary, so one inside test per
  // 8-connected component of far cells decides the whole component.
  const std::vector<std::uint8_t> far = MeasureClearance(index);
  ClassifyFarCells(index.geometry(), far);

  LabelComponents();
}

std::vector<std::uint8_t> WalkPlanner::MeasureClearance(const GeometryIndex& index) {
  const std::size_t n = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  std::vector<Vec2> near;
  std::vector<std::uint8_t> far(n, 0);
  clearance_.assign(n, static_cast<float>(inflation_));
  for (std::size_t c = 0; c < n; ++c) {
    near.clear();
    const Vec2 center = CellCenter(static_cast<int>(c));
    index.NearbyClosestPoints(center, inflation_, &near);
    far[c] = near.empty() ? 1 : 0;
    for (const Vec2& q : near) {
      clearance_[c] = std::min(clearance_[c], static_cast<float>((q - center).norm()));
    }
  }
  return far;
}

void WalkPlanner::ClassifyFarCells(const StaticGeometry& geometry,
                                   const std::vector<std::uint8_t>& far) {
  const std::size_t n = far.size();
  free_.assign(n, 0);
  if (inflation_ > 0.75 * cell_) {
    std::vector<std::uint8_t> seen(n, 0);
    std::vector<int> stack, members;
    for (std::size_t c0 = 0; c0 < n; ++c0) {
      if (!far[c0] || seen[c0]) continue;
      members.clear();
      stack.assign(1, static_cast<int>(c0));
      seen[c0] = 1;
      while (!stack.empty()) {
        const int c = stack.back();
        stack.pop_back();
        members.push_back(c);
        const int cx = c % nx_, cy = c / nx_;
        for (const Neighbour& nb : kNeighbours) {
          const int x = cx + nb.dx, y = cy + nb.dy;
          if (x < 0 || y < 0 || x >= nx_ || y >= ny_) continue;
          const std::size_t m = static_cast<std::size_t>(y) * nx_ + x;
          if (far[m] && !seen[m]) {
            seen[m] = 1;
            stack.push_back(static_cast<int>(m));
          }
        }
      }
      const bool inside = geometry.IsInside(CellCenter(static_cast<int>(c0)));
      for (int m : members) SetInside(static_cast<std::size_t>(m), inside);
    }
  } else {
    for (std::size_t c = 0; c < n; ++c) {
      if (far[c]) SetInside(c, geometry.IsInside(CellCenter(static_cast<int>(c))));
    }
  }
}

void WalkPlanner::SetInside(std::size_t cell, bool inside) {
  free_[cell] = inside ? 0 : 1;
  if (inside) clearance_[cell] = 0.0f;
}

void WalkPlanner::LabelComponents() {
  const std::size_t n = free_.size();
  // Components under the A* move rule (diagonals only between free orthogonal cells).
  component_.assign(n, -1);
  int next_id = 0;
  std::vector<int> stack;
  for (std::size_t c0 = 0; c0 < n; ++c0) {
    if (!free_[c0] || component_[c0] >= 0) continue;
    component_[c0] = next_id;
    stack.assign(1, static_cast<int>(c0));
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      const int cx = c % nx_, cy = c / nx_;
      for (const Neighbour& nb : kNeighbours) {
        const int x = cx + nb.dx, y = cy + nb.dy;
        if (x < 0 || y < 0 || x >= nx_ || y >= ny_) continue;
        const std::size_t m = static_cast<std::size_t>(y) * nx_ + x;
        if (!free_[m] || component_[m] >= 0) continue;
        if (nb.dx != 0 && nb.dy != 0 &&
            (!free_[static_cast<std::size_t>(cy) * nx_ + x] ||
             !free_[static_cast<std::size_t>(y) * nx_ + cx])) {
          continue;
        }
        component_[m] = next_id;
        stack.push_back(static_cast<int>(m));
      }
    }
    ++next_id;
  }
}

void WalkPlanner::AddObstacles(const StaticGeometry& solids) {
  std::size_t ring_edges = 0;
  for (const auto& ring : solids.polygons()) ring_edges += ring.size();
  RETRACE_CHECK(ring_edges == solids.segments().size() && solids.masks().empty());
  // Only the cells within the inflation radius of a solid's bounding box can change. Indices
  // are clamped in double first so that far-away solids cannot overflow an int.
  auto cell_index = [&](double v, double o, int count) {
    return static_cast<int>(
        std::clamp(std::floor((v - o) / cell_), -1.0, static_cast<double>(count)));
  };
  bool changed = false;
  auto block = [&](const Aabb& box, const auto& distance) {
    const double r = inflation_;
    const int x0 = std::max(0, cell_index(box.min.x() - r, origin_.x(), nx_));
    const int y0 = std::max(0, cell_index(box.min.y() - r, origin_.y(), ny_));
    const int x1 = std::min(nx_ - 1, cell_index(box.max.x() + r, origin_.x(), nx_));
    const int y1 = std::min(ny_ - 1, cell_index(box.max.y() + r, origin_.y(), ny_));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
        const double d = distance(CellCenter(static_cast<int>(c)));
        if (d >= inflation_) continue;
        changed = changed || free_[c] != 0;
        free_[c] = 0;
        clearance_[c] = std::min(clearance_[c], static_cast<float>(d));
      }
    }
  };
  for (const auto& ring : solids.polygons()) {
    Aabb box{ring.front(), ring.front()};
    for (const Vec2& v : ring) {
      box.min = box.min.cwiseMin(v);
      box.max = box.max.cwiseMax(v);
    }
    block(box, [&ring](const Vec2& p) {
      if (PointInPolygon(ring, p)) return 0.0;
      double d = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Segment s{ring[i], ring[(i + 1) % ring.size()]};
        d = std::min(d, core::SegmentDistance(p, s.a, s.b));
      }
      return d;
    });
  }
  for (const Circle& circle : solids.circles()) {
    const Vec2 r(circle.radius, circle.radius);
    block(Aabb{circle.center - r, circle.center + r}, [&circle](const Vec2& p) {
      return std::max(0.0, (p - circle.center).norm() - circle.radius);
    });
  }
  if (changed) LabelComponents();
}

Aabb WalkPlanner::area() const { return {origin_, origin_ + Vec2(nx_ * cell_, ny_ * cell_)}; }

int WalkPlanner::free_cell_count() const {
  return static_cast<int>(std::count(free_.begin(), free_.end(), std::uint8_t{1}));
}

int WalkPlanner::CellOf(const Vec2& p) const {
  if (!p.allFinite()) return -1;
  const double fx = std::floor((p.x() - origin_.x()) / cell_);
  const double fy = std::floor((p.y() - origin_.y()) / cell_);
  if (fx < 0.0 || fy < 0.0 || fx >= nx_ || fy >= ny_) return -1;
  return static_cast<int>(fy) * nx_ + static_cast<int>(fx);
}

Vec2 WalkPlanner::CellCenter(int cell) const {
  return origin_ + Vec2((cell % nx_ + 0.5) * cell_, (cell / nx_ + 0.5) * cell_);
}

bool WalkPlanner::IsFree(const Vec2& p) const {
  const int c = CellOf(p);
  return c >= 0 && free_[static_cast<std::size_t>(c)] != 0;
}

int WalkPlanner::Component(const Vec2& p) const {
  const int c = CellOf(p);
  return c >= 0 ? component_[static_cast<std::size_t>(c)] : -1;
}

bool WalkPlanner::LineOfSight(const Vec2& a, const Vec2& b) const {
  return Traverse(a, b, -1.0, /*skip_start=*/false);
}

bool WalkPlanner::ClearPath(const Vec2& a, const Vec2& b, double min_clearance) const {
  return Traverse(a, b, min_clearance, /*skip_start=*/true);
}

bool WalkPlanner::Traverse(const Vec2& a, const Vec2& b, double min_clearance,
                           bool skip_start) const {
  return TraverseFraction(a, b, min_clearance, skip_start) >= 1.0;
}

double WalkPlanner::TraverseFraction(const Vec2& a, const Vec2& b, double min_clearance,
                                     bool skip_start) const {
  // Amanatides & Woo grid traversal; when the segment passes exactly through a cell corner,
  // both cells beside the corner must pass.
  int c = CellOf(a);
  const int c_end = CellOf(b);
  if (c < 0 || c_end < 0) return 0.0;
  int x = c % nx_, y = c / nx_;
  const int x_end = c_end % nx_, y_end = c_end / nx_;
  auto free_at = [&](int cx, int cy) {
    if (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) return false;
    const std::size_t m = static_cast<std::size_t>(cy) * nx_ + cx;
    return min_clearance < 0.0 ? free_[m] != 0 : clearance_[m] >= min_clearance;
  };
  if (!skip_start && !free_at(x, y)) return 0.0;
  const Vec2 d = b - a;
  const int step_x = d.x() > 0.0 ? 1 : (d.x() < 0.0 ? -1 : 0);
  const int step_y = d.y() > 0.0 ? 1 : (d.y() < 0.0 ? -1 : 0);
  const double inf = std::numeric_limits<double>::infinity();
  const double t_dx = step_x != 0 ? cell_ / std::abs(d.x()) : inf;
  const double t_dy = step_y != 0 ? cell_ / std::abs(d.y()) : inf;
  const double bx = origin_.x() + (x + (step_x > 0 ? 1 : 0)) * cell_;
  const double by = origin_.y() + (y + (step_y > 0 ? 1 : 0)) * cell_;
  double t_x = step_x != 0 ? (bx - a.x()) / d.x() : inf;
  double t_y = step_y != 0 ? (by - a.y()) / d.y() : inf;
  const int max_steps = std::abs(x_end - x) + std::abs(y_end - y) + 2;
  for (int i = 0; i < max_steps && (x != x_end || y != y_end); ++i) {
    const double t_enter = std::min(t_x, t_y);  // where the next cell begins (segment fraction)
    if (std::abs(t_x - t_y) < 1e-12) {
      if (!free_at(x + step_x, y) || !free_at(x, y + step_y)) return t_enter;
      x += step_x;
      y += step_y;
      t_x += t_dx;
      t_y += t_dy;
    } else if (t_x < t_y) {
      x += step_x;
      t_x += t_dx;
    } else {
      y += step_y;
      t_y += t_dy;
    }
    if (!free_at(x, y)) return t_enter;
  }
  return 1.0;
}

double WalkPlanner::FreeLength(const Vec2& from, const Vec2& direction, double max_length,
                               double min_clearance) const {
  const double fraction = TraverseFraction(from, from + max_length * direction,
                                           std::min(min_clearance, inflation_), true);
  return std::clamp(fraction, 0.0, 1.0) * max_length;
}

std::optional<int> WalkPlanner::NearestFreeCell(const Vec2& p, double max_distance,
                                                int component) const {
  const int r = static_cast<int>(std::ceil(max_distance / cell_)) + 1;
  const int px = static_cast<int>(std::floor((p.x() - origin_.x()) / cell_));
  const int py = static_cast<int>(std::floor((p.y() - origin_.y()) / cell_));
  std::optional<int> best;
  double best_d2 = max_distance * max_distance;
  for (int y = std::max(0, py - r); y <= std::min(ny_ - 1, py + r); ++y) {
    for (int x = std::max(0, px - r); x <= std::min(nx_ - 1, px + r); ++x) {
      const int c = y * nx_ + x;
      if (!free_[static_cast<std::size_t>(c)]) continue;
      if (component >= 0 && component_[static_cast<std::size_t>(c)] != component) continue;
      const double d2 = (CellCenter(c) - p).squaredNorm();
      if (d2 <= best_d2) {
        if (best && d2 == best_d2) continue;  // keep the lower index on ties
        best_d2 = d2;
        best = c;
      }
    }
  }
  return best;
}

std::optional<Vec2> WalkPlanner::NearestFree(const Vec2& p, double max_distance,
                                             int component) const {
  const auto c = NearestFreeCell(p, max_distance, component);
  if (!c) return std::nullopt;
  return CellCenter(*c);
}

std::vector<int> WalkPlanner::AStar(int start, int goal) const {
  const std::size_t n = free_.size();
  if (g_.size() != n) {
    g_.assign(n, 0.0);
    parent_.assign(n, -1);
    stamp_.assign(n, 0);
  }
  if (++search_ == 0) {  // stamp wrap-around: invalidate everything
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    search_ = 1;
  }
  const int gx = goal % nx_, gy = goal / nx_;
  auto heuristic = [&](int c) {  // octile distance in cells
    const double dx = std::abs(c % nx_ - gx), dy = std::abs(c / nx_ - gy);
    return std::max(dx, dy) + (kSqrt2 - 1.0) * std::min(dx, dy);
  };
  using Entry = std::pair<double, int>;  // (f, cell); ties go to the lower cell index
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  stamp_[start] = search_;
  g_[start] = 0.0;
  parent_[start] = -1;
  open.emplace(heuristic(start), start);
  while (!open.empty()) {
    const auto [f, c] = open.top();
    open.pop();
    if (f > g_[c] + heuristic(c) + 1e-9) continue;  // stale entry
    if (c == goal) break;
    const int cx = c % nx_, cy = c / nx_;
    for (const Neighbour& nb : kNeighbours) {
      const int x = cx + nb.dx, y = cy + nb.dy;
      if (x < 0 || y < 0 || x >= nx_ || y >= ny_) continue;
      const int m = y * nx_ + x;
      if (!free_[m]) continue;
      if (nb.dx != 0 && nb.dy != 0 && (!free_[cy * nx_ + x] || !free_[y * nx_ + cx])) continue;
      const double g = g_[c] + nb.cost;
      if (stamp_[m] == search_ && g >= g_[m]) continue;
      stamp_[m] = search_;
      g_[m] = g;
      parent_[m] = c;
      open.emplace(g + heuristic(m), m);
    }
  }
  if (stamp_[goal] != search_) return {};
  std::vector<int> cells;
  for (int c = goal; c != -1; c = parent_[c]) cells.push_back(c);
  std::reverse(cells.begin(), cells.end());
  return cells;
}

std::optional<std::vector<Vec2>> WalkPlanner::Plan(const Vec2& from, const Vec2& to,
                                                   double max_snap) const {
  // Goal: `to` itself if free, else the nearest free cell.
  int goal = CellOf(to);
  Vec2 goal_point = to;
  if (goal < 0 || !free_[static_cast<std::size_t>(goal)]) {
    const auto snapped = NearestFreeCell(to, max_snap, -1);
    if (!snapped) return std::nullopt;
    goal = *snapped;
    goal_point = CellCenter(goal);
  }
  const int component = component_[static_cast<std::size_t>(goal)];
  // Start: `from` if free, else the nearest free cell (of any component: snapping into the
  // goal's component could jump through a thin wall); it must be connected to the goal.
  int start = CellOf(from);
  bool start_snapped = false;
  if (start < 0 || !free_[static_cast<std::size_t>(start)]) {
    const auto snapped = NearestFreeCell(from, max_snap, -1);
    if (!snapped) return std::nullopt;
    start = *snapped;
    start_snapped = true;
  }
  if (component_[static_cast<std::size_t>(start)] != component) return std::nullopt;
  const Vec2 start_point = start_snapped ? CellCenter(start) : from;
  std::vector<Vec2> out;
  if (start_snapped) out.push_back(start_point);
  if (start == goal) {
    out.push_back(goal_point);
    return out;
  }
  const std::vector<int> cells = AStar(start, goal);
  RETRACE_CHECK(!cells.empty());  // same component, so a path exists
  std::vector<Vec2> points;
  points.reserve(cells.size());
  points.push_back(start_point);
  for (std::size_t i = 1; i + 1 < cells.size(); ++i) points.push_back(CellCenter(cells[i]));
  points.push_back(goal_point);
  // Greedy line-of-sight shortcutting: from each anchor, the farthest visible successor.
  std::size_t i = 0;
  const std::size_t last = points.size() - 1;
  while (i < last) {
    std::size_t j = i + 1;
    while (j < last && LineOfSight(points[i], points[j + 1])) ++j;
    out.push_back(points[j]);
    i = j;
  }
  return out;
}

std::optional<Vec2> WalkPlanner::SampleFreePoint(const Aabb& region, core::Rng& rng, int max_tries,
                                                 int component) const {
  for (int t = 0; t < max_tries; ++t) {
    const Vec2 p(rng.Uniform(region.min.x(), region.max.x()),
                 rng.Uniform(region.min.y(), region.max.y()));
    const int c = CellOf(p);
    if (c < 0 || !free_[static_cast<std::size_t>(c)]) continue;
    if (component >= 0 && component_[static_cast<std::size_t>(c)] != component) continue;
    return p;
  }
  return std::nullopt;
}

Aabb PlanningArea(const std::vector<Aabb>& regions, const std::vector<Vec2>& points,
                  double padding) {
  const double inf = std::numeric_limits<double>::infinity();
  Aabb box{{inf, inf}, {-inf, -inf}};
  for (const Aabb& r : regions) {
    box.min = box.min.cwiseMin(r.min);
    box.max = box.max.cwiseMax(r.max);
  }
  for (const Vec2& p : points) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  if (!(box.min.x() <= box.max.x())) return {};
  box.min -= Vec2(padding, padding);
  box.max += Vec2(padding, padding);
  return box;
}

}  // namespace retrace::sim
