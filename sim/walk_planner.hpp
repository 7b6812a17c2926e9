#pragma once
// Where pedestrians can walk: a coarse occupancy grid of the static geometry inflated by the
// pedestrian radius plus a margin, A* over it and line-of-sight shortcutting into a few
// waypoints, so that pedestrians go round walls instead of pushing against them forever.
// Also samples random free, reachable points of a region.

#include <cstdint>
#include <optional>
#include <vector>

#include "core/config.hpp"
#include "core/rng.hpp"
#include "sim/geometry_index.hpp"
#include "sim/static_geometry.hpp"

namespace retrace::sim {

/// Grid resolution and safety margin of the walk planner.
struct WalkPlannerConfig {
  /// m; 0.1 m resolves doors to within a few cm and keeps a 50 m x 50 m area at 250k cells.
  double cell_size = 0.1;
  /// m added to the pedestrian radius when inflating. Line-of-sight segments run through free
  /// cells only, so their clearance is at least radius + margin - cell_size / sqrt(2).
  double margin = 0.1;
  /// m around the pedestrian regions and loop waypoints that the grid also covers, for detours.
  double area_padding = 5.0;

  template <class V>
  void Reflect(V& v) {
    v("cell_size", cell_size);
    v("margin", margin);
    v("area_padding", area_padding);
  }
  /// Throws core::ConfigError naming the key: cell_size in [0.02, 2] m, margin and
  /// area_padding >= 0.
  void Validate() const;
};

/// The cell size (m) a planner over `area` uses: config.cell_size, or, when that would need
/// more than 8 million cells, the smallest coarser one (in whole centimetres) that does not.
double PlanningCellSize(const Aabb& area, const WalkPlannerConfig& config);

class WalkPlanner {
 public:
  /// Rasterises `area` (W, m) in cells of PlanningCellSize(area, config): a cell is free when
  /// its centre lies outside every solid with clearance >= pedestrian_radius + config.margin.
  /// Keeps no reference to `index`. Throws core::ConfigError on an invalid config,
  /// core::WorldError if the area is empty or would need cells coarser than 0.5 m.
  WalkPlanner(const GeometryIndex& index, const Aabb& area, double pedestrian_radius,
              const WalkPlannerConfig& config);

  /// Blocks the cells whose centre lies inside or within inflation_radius() of a polygon or
  /// circle of `solids` (obstacles added at run time; open edges are not supported: checked),
  /// and recomputes the connected components. Component ids may change.
  void AddObstacles(const StaticGeometry& solids);

  /// Clearance radius (m) the free cells guarantee at their centres.
  double inflation_radius() const { return inflation_; }
  /// The rasterised area (W, m): the requested one rounded up to whole cells.
  Aabb area() const;
  double cell_size() const { return cell_; }
  int width() const { return nx_; }
  int height() const { return ny_; }
  int free_cell_count() const;

  /// True if p (W) lies in a free cell of the grid.
  bool IsFree(const Vec2& p) const;
  /// Id (>= 0) of the connected free component that contains p, or -1 if p is not free.
  /// Two points with the same id are connected by a walkable path.
  int Component(const Vec2& p) const;
  /// True if every grid cell the segment a-b passes through is free.
  bool LineOfSight(const Vec2& a, const Vec2& b) const;
  /// True if every grid cell the segment a-b passes through, except the one containing a, has
  /// a centre clearance >= min_clearance (m; capped at inflation_radius()). A looser test than
  /// LineOfSight for "can I still walk straight to my waypoint from here".
  bool ClearPath(const Vec2& a, const Vec2& b, double min_clearance) const;

  /// How far (m) one can walk from `from` along the unit vector `direction`, up to max_length,
  /// before entering a cell whose centre clearance is below min_clearance (m; capped at
  /// inflation_radius()); the cell holding `from` is not tested. 0 outside the grid.
  double FreeLength(const Vec2& from, const Vec2& direction, double max_length,
                    double min_clearance) const;

  /// Waypoints (W) from `from` to `to`, excluding `from` and ending at `to` (or at the nearest
  /// free cell centre if `to` is not free). A start or goal that is not free is snapped to the
  /// nearest free cell within max_snap (m). nullopt if no walkable path exists.
  std::optional<std::vector<Vec2>> Plan(const Vec2& from, const Vec2& to,
                                        double max_snap = 1.5) const;

  /// A uniform random free point of `region` (W); if component >= 0, only points of that
  /// component (reachable from it). nullopt after max_tries rejected samples.
  std::optional<Vec2> SampleFreePoint(const Aabb& region, core::Rng& rng, int max_tries,
                                      int component = -1) const;

  /// Centre of the free cell nearest to p within max_distance (m), restricted to `component`
  /// if >= 0; nullopt if there is none.
  std::optional<Vec2> NearestFree(const Vec2& p, double max_distance, int component = -1) const;

 private:
  int CellOf(const Vec2& p) const;  // -1 outside the grid
  Vec2 CellCenter(int cell) const;
  // Construction steps: each cell's clearance (returns which cells are "far": nothing within
  // the inflation radius), then free or blocked for every far cell by an inside test.
  std::vector<std::uint8_t> MeasureClearance(const GeometryIndex& index);
  void ClassifyFarCells(const StaticGeometry& geometry, const std::vector<std::uint8_t>& far);
  void SetInside(std::size_t cell, bool inside);  // blocked, clearance 0, if inside a solid
  void LabelComponents();
  std::optional<int> NearestFreeCell(const Vec2& p, double max_distance, int component) const;
  std::vector<int> AStar(int start, int goal) const;
  // Grid traversal: min_clearance < 0 means "free cells only".
  bool Traverse(const Vec2& a, const Vec2& b, double min_clearance, bool skip_start) const;
  // The fraction of a-b walked before the first cell that fails (1: none fails).
  double TraverseFraction(const Vec2& a, const Vec2& b, double min_clearance,
                          bool skip_start) const;

  double cell_;
  double inflation_;
  Vec2 origin_;
  int nx_ = 0;
  int ny_ = 0;
  std::vector<std::uint8_t> free_;
  std::vector<float> clearance_;  // centre clearance (m), capped at inflation_; 0 inside solids
  std::vector<int> component_;    // -1 for blocked cells
  // A* scratch, reused between calls; a cell's entries are valid when its stamp matches.
  mutable std::vector<double> g_;
  mutable std::vector<int> parent_;
  mutable std::vector<std::uint32_t> stamp_;
  mutable std::uint32_t search_ = 0;
};

/// The box around `regions` and `points`, grown by `padding` (m) on every side.
Aabb PlanningArea(const std::vector<Aabb>& regions, const std::vector<Vec2>& points,
                  double padding);

}  // namespace retrace::sim
