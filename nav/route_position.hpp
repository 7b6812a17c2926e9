#pragma once
// The robot's place on the taught route (docs/METHOD.md, "The map server"): a map, an arc length
// along that map's taught path, and a direction of travel — forward along the taught drive, or
// backward. The map server decides by it: the end of a path driven forward leads into the next
// map (eq. 1), the start of a path driven backward into the previous one (eq. 1 inverted), and
// the arc length is continuous: it moves along the path no faster than the robot drives, so a
// street the route drove twice is never mistaken for the stretch the robot is on.

#include <cstdint>

#include "core/path.hpp"
#include "core/pose2.hpp"

namespace retrace::nav {

/// Direction of travel along a taught path.
enum class Travel : std::int8_t {
  kBackward = -1,
  kUnknown = 0,
  kForward = 1,
};

/// The arc length moves by this much (m) in one direction before the direction of travel is
/// taken to be that one: a robot that stands, or wobbles at a stop, keeps its direction.
inline constexpr double kTravelHysteresis = 0.5;

/// The robot's place on one taught path, tracked from one estimate to the next.
struct RoutePosition {
  std::size_t map = 0;
  double s = 0.0;         ///< m: arc length of the projection, within [0, path length]
  /// m: the arc length extended beyond the path's ends along their tangents: < 0 behind the
  /// start, > path length past the end (equal to s between them).
  double s_extended = 0.0;
  double distance = 0.0;  ///< m from the estimate to the path at s
  bool on_path = true;    ///< distance within the tracker's max_distance
  double off_path_driven = 0.0;  ///< m the estimate moved since it was last on the path
  Travel travel = Travel::kUnknown;
};

/// Tracks the estimate's place along the current map's taught path: the projection is searched
/// only within window + (distance driven since the place was last on the path) of arc length
/// either side of the last one, so it follows the robot continuously in both directions and never
/// jumps to another part of a path that passes nearby.
class RouteTracker {
 public:
  /// Starts on `path` (which must outlive the tracker's use of it, until the next Reset) of map
  /// `map` at arc length s. The direction of travel: `travel` if known, else from the estimate's
  /// heading against the path's (forward within ±60°, backward within ±60° of the opposite).
  void Reset(const core::Path& path, std::size_t map, double s, const core::Pose2& X_MR,
             Travel travel);
  /// Moves the place with the estimate X_MR (in the path's map). window (m): the arc length the
  /// projection may move beyond the robot's own motion; max_distance (m): farther from the path
  /// than this, the place waits where the robot left it (on_path false).
  const RoutePosition& Update(const core::Pose2& X_MR, double window, double max_distance);
  const RoutePosition& position() const { return position_; }

 private:
  const core::Path* path_ = nullptr;
  RoutePosition position_;
  core::Vec2 last_xy_ = core::Vec2::Zero();
  double slack_ = 0.0;   // m driven since the place was last on the path
  double anchor_ = 0.0;  // s where the direction of travel was last confirmed
};

/// The direction of a heading against a path's at arc length s: forward when within ±60° of
/// it, backward within ±60° of the opposite, else unknown.
Travel TravelOf(const core::Path& path, double s, double heading);

}  // namespace retrace::nav
