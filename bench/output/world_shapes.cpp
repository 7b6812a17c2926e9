#include "bench/output/world_shapes.hpp"

#include <array>
#include <set>

namespace retrace::bench {

viz::WorldShapes WorldShapesOf(const sim::StaticGeometry& geometry) {
  viz::WorldShapes shapes;
  shapes.polygons = geometry.polygons();
  for (const sim::Circle& c : geometry.circles()) shapes.circles.push_back({c.center, c.radius});
  // segments() holds the polygons' own edges too (in any order with imported edges); those are
  // drawn as the filled polygons.
  std::set<std::array<double, 4>> outline;
  for (const auto& ring : geometry.polygons()) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const sim::Vec2& a = ring[i];
      const sim::Vec2& b = ring[(i + 1) % ring.size()];
      outline.insert({a.x(), a.y(), b.x(), b.y()});
    }
  }
  for (const sim::Segment& s : geometry.segments()) {
    if (!outline.contains({s.a.x(), s.a.y(), s.b.x(), s.b.y()}))
      shapes.segments.emplace_back(s.a, s.b);
  }
  return shapes;
}

}  // namespace retrace::bench
