#pragma once
// A floor for the pedestrian tests: two rooms, a corridor and a hall joined by doors, and the
// crowd that walks it.

#include <vector>

#include "sim/pedestrians.hpp"
#include "sim/static_geometry.hpp"
#include "tests/sim/add_box.hpp"
#include "tests/support/pedestrian_group.hpp"

namespace retrace::sim::testing_floor {

using retrace::testing::Group;

using test_geometry::AddBox;

// 24 m x 14 m: two rooms at the bottom, a 2 m corridor across the middle and a hall on top
// with a pillar and a table; 1.2 m doors.
inline StaticGeometry RoomsAndCorridor() {
  StaticGeometry g;
  AddBox(g, -0.2, -0.2, 24.2, 0.0);
  AddBox(g, -0.2, 14.0, 24.2, 14.2);
  AddBox(g, -0.2, 0.0, 0.0, 14.0);
  AddBox(g, 24.0, 0.0, 24.2, 14.0);
  // Between the bottom rooms and the corridor, doors at x in [4.4, 5.6] and [18.4, 19.6].
  AddBox(g, 0.0, 5.8, 4.4, 6.0);
  AddBox(g, 5.6, 5.8, 18.4, 6.0);
  AddBox(g, 19.6, 5.8, 24.0, 6.0);
  // Between the corridor and the hall, doors at x in [2.4, 3.6] and [20.4, 21.6].
  AddBox(g, 0.0, 8.0, 2.4, 8.2);
  AddBox(g, 3.6, 8.0, 20.4, 8.2);
  AddBox(g, 21.6, 8.0, 24.0, 8.2);
  AddBox(g, 11.9, 0.0, 12.1, 5.8);  // between the bottom rooms
  g.AddCircle({{12.0, 11.0}, 0.5});
  AddBox(g, 6.0, 10.0, 8.0, 11.5);
  return g;
}

inline std::vector<PedestrianGroupConfig> RoomsAndCorridorGroups() {
  return {Group(5, {0.0, 0.0}, {11.9, 5.8}), Group(5, {12.1, 0.0}, {24.0, 5.8}),
          Group(4, {0.0, 8.2}, {24.0, 14.0}),
          Group(6, {1.0, 6.2}, {23.0, 7.8}, PedestrianMode::kLoop,
                {{5.0, 3.0}, {3.0, 11.0}, {21.0, 11.0}, {19.0, 3.0}})};
}

}  // namespace retrace::sim::testing_floor
