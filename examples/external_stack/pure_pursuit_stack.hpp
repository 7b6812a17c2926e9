#pragma once
// A navigation stack that is not retrace's: the taught paths replayed on odometry alone, by pure
// pursuit, with a stop while the scan shows something just ahead. It speaks to the harness only
// through bench/stack/navigation_stack.hpp (odometry, scans and time in; the command, the
// estimate in a taught map's frame and that map out), as docs/PYTHON.md's Python stack does.

#include <cstddef>
#include <vector>

#include "bench/stack/navigation_stack.hpp"
#include "core/pose2.hpp"

namespace external {

/// One taught map as this stack uses it: its path (poses in the map's frame) and the switch pose
/// X_MS, where the next map's frame starts.
struct TaughtPath {
  std::vector<retrace::core::Pose2> poses;
  retrace::core::Pose2 X_MS;
};

struct PurePursuitOptions {
  double speed = 0.6;          ///< m/s
  double lookahead = 0.8;      ///< m: the path point steered at
  double stop_distance = 0.25;  ///< m beyond the robot's radius: an obstacle this close stops it
  double robot_radius = 0.3;   ///< m
};

class PurePursuitStack final : public retrace::bench::NavigationStack {
 public:
  PurePursuitStack(std::vector<TaughtPath> paths, PurePursuitOptions options);

  void OnOdometry(double t, const retrace::core::OdometryDelta& delta) override;
  void OnScan(const retrace::core::LaserScan& scan) override;
  retrace::bench::StackOutput OnControlTick(double t, double dt) override;

 private:
  std::vector<TaughtPath> paths_;
  PurePursuitOptions options_;
  std::size_t map_ = 0;          // the taught map the estimate is in
  std::size_t reached_ = 0;      // the point of its path reached
  retrace::core::Pose2 X_MR_;    // dead reckoning; map 0's frame is where the drive began
  bool blocked_ = false;
};

/// Registers the stack as `pure_pursuit`, with its options speed, lookahead and stop_distance
/// (playback.stack_options).
void RegisterPurePursuit();

}  // namespace external
