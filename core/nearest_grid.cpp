#include "core/nearest_grid.hpp"

#include "core/check.hpp"

namespace retrace::core {
namespace {

constexpr double kMaxCellIndex = 1 << 30;  // |cell index|, so that keys stay unique

}  // namespace

NearestGrid::NearestGrid(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double cell)
    : cell_(cell) {
  RETRACE_CHECK(a.size() == b.size());
  RETRACE_CHECK(cell > 0.0 && std::isfinite(cell));
  // Every segment is cut into pieces no longer than a cell; a piece's bounding box covers at
  // most 2 x 2 cells, and the segment is listed in each of them: so in the cell of each of its
  // points, which is what the ring search needs.
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double len = (b[i] - a[i]).norm();
    const auto pieces = static_cast<std::size_t>(std::max(1.0, std::ceil(len / cell_)));
    for (std::size_t k = 0; k < pieces; ++k) {
      const Vec2 p0 = a[i] + (b[i] - a[i]) * (static_cast<double>(k) / static_cast<double>(pieces));
      const Vec2 p1 =
          a[i] + (b[i] - a[i]) * (static_cast<double>(k + 1) / static_cast<double>(pieces));
      for (std::int64_t x = Cell(std::min(p0.x(), p1.x())); x <= Cell(std::max(p0.x(), p1.x()));
           ++x) {
        for (std::int64_t y = Cell(std::min(p0.y(), p1.y())); y <= Cell(std::max(p0.y(), p1.y()));
             ++y) {
          entries_.push_back({Key(x, y), i});
          lo_x_ = entries_.size() == 1 ? x : std::min(lo_x_, x);
          hi_x_ = entries_.size() == 1 ? x : std::max(hi_x_, x);
          lo_y_ = entries_.size() == 1 ? y : std::min(lo_y_, y);
          hi_y_ = entries_.size() == 1 ? y : std::max(hi_y_, y);
        }
      }
    }
  }
  std::sort(entries_.begin(), entries_.end());
  entries_.erase(std::unique(entries_.begin(), entries_.end()), entries_.end());
}

double NearestGrid::CellForExtent(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  if (a.empty()) return 1.0;
  Vec2 lo = a[0], hi = a[0];
  for (std::size_t i = 0; i < a.size(); ++i) {
    lo = lo.cwiseMin(a[i]).cwiseMin(b[i]);
    hi = hi.cwiseMax(a[i]).cwiseMax(b[i]);
  }
  const Vec2 extent = hi - lo;
  // 1 m cells hold a few dozen samples of a taught path.
  return std::max(1.0, std::max(extent.x(), extent.y()) / 1024.0);
}

std::int64_t NearestGrid::Cell(double v) const {
  // Clamped so that the cast is defined for any input.
  return static_cast<std::int64_t>(
      std::clamp(std::floor(v / cell_), -kMaxCellIndex, kMaxCellIndex));
}

}  // namespace retrace::core
