#pragma once
// How close people come to each other when they pass: a pair of pedestrians whose centres come
// within an encounter radius is in an encounter until they are farther apart again (or the
// measurement ends); it is a pass when their order round the ring's centre (the origin) changes
// meanwhile, one overtaking the other or the two walking past each other, and its closest
// approach is the smallest distance between their centres meanwhile. Neighbours who only walk
// side by side or one behind the other are not passes. Pure bookkeeping over positions; nothing
// here knows the simulator.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/pose2.hpp"

namespace retrace::bench {

/// The closest approaches of the passes seen so far.
struct ClosestApproachStats {
  std::int64_t encounters = 0;  ///< passes closed
  double mean = 0.0;            ///< m between centres, mean over passes (NaN: none)
  double p05 = 0.0;             ///< m, 5th percentile (NaN: none)
};

class ClosestApproachTracker {
 public:
  /// `people` pedestrians, indexed 0..people-1; encounters begin within `radius` (m, > 0).
  ClosestApproachTracker(std::size_t people, double radius);

  /// Looks at every pair (positions in W, m, one per person): pairs within the radius that were
  /// not in an encounter begin one. Cost: quadratic in the people; call it often enough that no
  /// pair crosses the radius and comes closest between two calls (every 0.2 s at walking
  /// speeds for a radius of 2 m).
  void OpenEncounters(const std::vector<core::Vec2>& positions);
  /// Updates the encounters in progress with the positions now; ends those that moved apart.
  /// Cheap (only the open pairs): call it every step.
  void Update(const std::vector<core::Vec2>& positions);
  /// Ends every encounter in progress (the measurement is over) and returns the statistics.
  ClosestApproachStats Finish();

 private:
  // Ends encounter k: a pass (the pair's order round the origin changed) is recorded.
  void Close(std::uint32_t k);

  std::size_t people_;
  double radius_;
  std::vector<double> open_min_;   // per pair i < j (i * people + j): smallest distance, < 0 closed
  std::vector<std::int8_t> side_;  // per pair: the sign of p_i x p_j when the encounter began
  std::vector<std::uint8_t> passed_;  // per pair: that sign changed since
  std::vector<std::uint32_t> open_;   // pairs in an encounter, as i * people + j
  std::vector<double> closed_;        // closest approaches of the ended passes (m)
};

}  // namespace retrace::bench
