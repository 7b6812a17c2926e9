#pragma once
// Random looped tours for stress-testing map switching: a street grid of random block sizes and a
// route along its streets made of loops round rectangles of blocks, chained by short transfers.
// Every loop comes back to where it began and later loops drive streets that earlier ones drove,
// so a tour revisits itself many times, in both directions and at crossings — what partial maps
// and their switch points must cope with. No U-turns, unless out_and_back asks for legs that go
// along a street and come straight back along it.
// Pure and deterministic: the same config and seed give the same route. `retrace generate-tour`
// builds a campus world round it (campus_generator.hpp) and a scenario.

#include <array>
#include <cstdint>
#include <vector>

#include "core/config.hpp"
#include "core/pose2.hpp"

namespace retrace::bench {

struct TourConfig {
  double length = 700.0;  ///< m: the tour ends at the first crossing at or past this length
  int columns = 4;        ///< blocks of the grid, west to east
  int rows = 3;           ///< blocks of the grid, south to north
  std::array<double, 2> block_size{30.0, 60.0};  ///< m, [min, max] of each column's and row's size
  int max_loop_blocks = 2;  ///< a loop goes round at most this many blocks in each direction
  int max_transfer = 2;     ///< streets driven between two loops: 1 to this many
  /// Out-and-back legs: after each of the first this many loops, the route drives 1 to
  /// max_transfer streets on and comes back along them (a U-turn at the far crossing), so that
  /// it drives the same street both ways in a row. 0: none (the tour as without the key).
  int out_and_back = 0;

  template <class V>
  void Reflect(V& v) {
    v("length", length);
    v("columns", columns);
    v("rows", rows);
    v("block_size", block_size);
    v("max_loop_blocks", max_loop_blocks);
    v("max_transfer", max_transfer);
    v("out_and_back", out_and_back);
  }
  /// Throws core::ConfigError naming the key: length in (0, 100 km], 1..50 columns and rows,
  /// block sizes 10..500 m with min <= max, max_loop_blocks >= 1, max_transfer >= 1,
  /// out_and_back 0..1000.
  void Validate() const;
};

/// The tour's waypoints (W, m; the grid's south-west crossing at the origin), one per crossing
/// the route turns or goes straight at. Throws core::ConfigError for an invalid config.
std::vector<core::Vec2> GenerateTour(const TourConfig& config, std::uint64_t seed);

}  // namespace retrace::bench
