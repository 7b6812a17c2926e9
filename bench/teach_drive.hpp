#pragma once
// The teaching drive: the simulated operator drives the route once while teach recorders build
// the maps of every requested mode from the same sensor data — so that the modes differ only
// in how the maps were made (DESIGN §6):
//   partial     odometry poses, a new map at every switch point (the paper's method)
//   single      odometry poses, one map
//   consistent  ground-truth poses relative to the start, one map (a perfect SLAM's map)

#include <functional>
#include <string>
#include <vector>

#include "bench/scenario.hpp"
#include "bench/trace.hpp"
#include "nav/teach_bundle.hpp"
#include "sim/collision_event.hpp"

namespace retrace::bench {

/// Called now and then with the simulated time (s) of a long loop, for progress displays.
using ProgressFn = std::function<void(double sim_time_s)>;

struct ModeTeach {
  MapMode mode = MapMode::kPartial;
  nav::TeachBundle bundle;
  TeachTrace trace;  ///< the drive's ground truth, with this mode's per-map references
};

struct TeachResult {
  double duration_s = 0.0;  ///< simulated
  double cpu_time_s = 0.0;
  std::vector<sim::CollisionEvent> collisions;
  std::vector<std::string> events;  ///< "time name" of each scripted event fired
  std::vector<ModeTeach> modes;     ///< in the order requested
};

/// Drives the route with the teacher and builds the bundles of `modes`. Throws
/// core::WorldError when the teacher does not finish the route within the teach timeout (a
/// route it cannot drive), with where it got stuck.
TeachResult RunTeachDrive(const Scenario& scenario, const std::vector<MapMode>& modes,
                          const ProgressFn& progress = {});

/// Thread CPU time (s), for the cost metrics; never used to decide anything in an episode.
double ThreadCpuSeconds();

}  // namespace retrace::bench
