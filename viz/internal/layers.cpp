#include "viz/internal/layers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace retrace::viz::internal {

void DrawWorld(GlCanvas& canvas, const WorldShapes& world) {
  const Box2 vis = canvas.view().VisibleBox();
  auto visible = [&](const Box2& b) {
    return !(b.max.x() < vis.min.x() || b.min.x() > vis.max.x() || b.max.y() < vis.min.y() ||
             b.min.y() > vis.max.y());
  };
  for (const auto& ring : world.polygons) {
    Box2 b;
    for (const Vec2& p : ring) b.Extend(p);
    if (visible(b)) canvas.FillPolygon(ring, palette::kWorldSolid);
  }
  for (const Circle& c : world.circles) {
    Box2 b;
    b.Extend(c.center, c.radius);
    if (visible(b)) canvas.FillDisc(c.center, c.radius, palette::kWorldSolid);
  }
  std::vector<std::pair<Vec2, Vec2>> edges;
  for (const auto& s : world.segments) {
    if (visible(Box2::Of(s.first, s.second))) edges.push_back(s);
  }
  // At least a pixel, and the true thickness of a thin wall (about 0.1 m) when zoomed in.
  canvas.DrawSegments(edges, std::max(1.2, 0.1 * canvas.view().pixels_per_meter()),
                      palette::kWorldEdge);
}

void DrawStart(GlCanvas& canvas, const Vec2& p) {
  canvas.DrawMarkers({p}, Marker::kDisc, kStartMarkerPx, palette::kStart, 2.0, palette::kText);
}

void DrawSwitches(GlCanvas& canvas, const std::vector<Vec2>& points) {
  canvas.DrawMarkers(points, Marker::kDiamond, kSwitchMarkerPx, palette::kSwitch, 1.5,
                     palette::kText);
}

LegendEntry StartLegend() {
  return {"start", palette::kStart, LegendSymbol::kMarker, Marker::kDisc, 7.0, true};
}
LegendEntry SwitchLegend() {
  return {"map switch", palette::kSwitch, LegendSymbol::kMarker, Marker::kDiamond, 8.0, true};
}
LegendEntry WorldLegend() {
  return {"buildings, walls, trees", palette::kWorldSolid, LegendSymbol::kPatch};
}

std::vector<std::pair<std::size_t, std::size_t>> SplitAtSwitches(
    const std::vector<core::Pose2>& route, const std::vector<core::Pose2>& switches) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  std::size_t begin = 0;
  for (const auto& s : switches) {
    const Vec2 p = s.translation();
    std::size_t split = route.size();
    // First visit within 1 m: follow it down to its closest point. A route that passes the
    // switch point again later (a loop) is thereby split at the right lap.
    for (std::size_t i = begin; i < route.size(); ++i) {
      if ((route[i].translation() - p).norm() < 1.0) {
        std::size_t best = i;
        double best_d = (route[i].translation() - p).norm();
        for (std::size_t j = i + 1; j < route.size(); ++j) {
          const double d = (route[j].translation() - p).norm();
          if (d > 1.0) break;
          if (d < best_d) {
            best_d = d;
            best = j;
          }
        }
        split = best;
        break;
      }
    }
    if (split == route.size()) {
      double best_d = std::numeric_limits<double>::infinity();
      for (std::size_t i = begin; i < route.size(); ++i) {
        const double d = (route[i].translation() - p).norm();
        if (d < best_d) {
          best_d = d;
          split = i;
        }
      }
    }
    if (split == route.size()) split = begin;
    out.emplace_back(begin, std::min(route.size(), split + 1));
    begin = split;
  }
  out.emplace_back(begin, route.size());
  return out;
}

Box2 WorldViewBox(const Box2& content, const WorldShapes& world) {
  const Box2 w = world.Bounds();
  if (content.IsEmpty()) return w;
  Box2 box = content.Inflated(std::clamp(0.1 * content.Size().maxCoeff(), 1.0, 10.0));
  if (!w.IsEmpty() && box.Inflated(0.3 * box.Size().maxCoeff()).Contains(w.min) &&
      box.Inflated(0.3 * box.Size().maxCoeff()).Contains(w.max)) {
    box.Extend(w);
  }
  return box;
}

double PathLength(const std::vector<core::Pose2>& poses) {
  double len = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) len += core::Distance(poses[i - 1], poses[i]);
  return len;
}

namespace {

// The box around the cells whose log-odds pass `keep`, carried by X_WM.
template <class Keep>
Box2 CellsBox(const core::OccupancyGrid& grid, const core::Pose2& X_WM, Keep keep) {
  int x0 = grid.width();
  int y0 = grid.height();
  int x1 = -1;
  int y1 = -1;
  const auto& lo = grid.log_odds();
  for (int y = 0; y < grid.height(); ++y) {
    const float* row = lo.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(grid.width());
    for (int x = 0; x < grid.width(); ++x) {
      if (keep(row[x])) {
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
      }
    }
  }
  Box2 box;
  if (x1 < 0) return box;
  const double r = grid.resolution();
  const Vec2 lo_M = grid.origin() + Vec2(x0 * r, y0 * r);
  const Vec2 hi_M = grid.origin() + Vec2((x1 + 1) * r, (y1 + 1) * r);
  for (const Vec2& c : {lo_M, hi_M, Vec2(lo_M.x(), hi_M.y()), Vec2(hi_M.x(), lo_M.y())}) {
    box.Extend(X_WM * c);
  }
  return box;
}

}  // namespace

Box2 KnownCellsBox(const core::OccupancyGrid& grid, const core::Pose2& X_WM) {
  return CellsBox(grid, X_WM, [](float l) { return l != 0.0f; });
}

Box2 OccupiedCellsBox(const core::OccupancyGrid& grid, const core::Pose2& X_WM) {
  const float l_occupied = static_cast<float>(core::Logit(0.65));
  return CellsBox(grid, X_WM, [l_occupied](float l) { return l >= l_occupied; });
}

}  // namespace retrace::viz::internal
