#include "bench/worldgen/tour_generator.hpp"

#include <algorithm>
#include <string>

#include "core/rng.hpp"

namespace retrace::bench {
namespace {

// Grid directions: east, north, west, south.
constexpr std::array<int, 4> kDx{1, 0, -1, 0};
constexpr std::array<int, 4> kDy{0, 1, 0, -1};

int Reverse(int dir) { return (dir + 2) % 4; }

struct Walker {
  explicit Walker(const TourConfig& c) : config(c) {}

  const TourConfig& config;
  std::vector<double> xs, ys;  // the grid lines
  int i = 0, j = 0;            // the current crossing
  int heading = -1;            // the last direction driven (-1: none yet)
  std::vector<core::Vec2> route;
  double length = 0.0;

  bool Inside(int a, int b) const {
    return a >= 0 && b >= 0 && a <= config.columns && b <= config.rows;
  }
  void Drive(int dir) {
    const core::Vec2 from(xs[i], ys[j]);
    i += kDx[dir];
    j += kDy[dir];
    const core::Vec2 to(xs[i], ys[j]);
    length += (to - from).norm();
    // Straight on through a crossing needs no waypoint: extend the last leg.
    if (heading == dir && route.size() >= 2) {
      route.back() = to;
    } else {
      route.push_back(to);
    }
    heading = dir;
  }
  // The directions of one lap round the rectangle of w × h blocks whose corner is here, going
  // out along `first` and turning left (+1) or right (-1) at each corner.
  static std::vector<int> Lap(int first, int turn, int w, int h) {
    std::vector<int> dirs;
    int dir = first;
    for (int side = 0; side < 4; ++side) {
      const int n = (dir == 0 || dir == 2) ? w : h;
      for (int k = 0; k < n; ++k) dirs.push_back(dir);
      dir = (dir + turn + 4) % 4;
    }
    return dirs;
  }
  // The directions that go on from here without turning back.
  std::vector<int> WaysOn() const {
    std::vector<int> ways;
    for (int d = 0; d < 4; ++d) {
      if ((heading < 0 || d != Reverse(heading)) && Inside(i + kDx[d], j + kDy[d]))
        ways.push_back(d);
    }
    return ways;
  }
  // An out-and-back leg: on along one to max_transfer streets, then straight back along them.
  void OutAndBack(core::Rng& rng) {
    const std::vector<int> ways = WaysOn();
    const int out = ways[rng.UniformIndex(ways.size())];
    const int streets =
        1 + static_cast<int>(rng.UniformIndex(static_cast<std::uint64_t>(config.max_transfer)));
    int driven = 0;
    while (driven < streets && Inside(i + kDx[out], j + kDy[out])) {
      Drive(out);
      ++driven;
    }
    for (int k = 0; k < driven; ++k) Drive(Reverse(out));
  }
  bool Fits(const std::vector<int>& dirs) const {
    int a = i, b = j;
    for (int d : dirs) {
      a += kDx[d];
      b += kDy[d];
      if (!Inside(a, b)) return false;
    }
    return true;
  }
};

}  // namespace

void TourConfig::Validate() const {
  core::RequireInRange("length", length, 1e-9, 1e5);
  core::RequireIntInRange("columns", columns, 1, 50);
  core::RequireIntInRange("rows", rows, 1, 50);
  core::RequireInRange("block_size", block_size[0], 10.0, 500.0);
  core::RequireInRange("block_size", block_size[1], block_size[0], 500.0);
  core::RequireIntInRange("max_loop_blocks", max_loop_blocks, 1, 50);
  core::RequireIntInRange("max_transfer", max_transfer, 1, 50);
  core::RequireIntInRange("out_and_back", out_and_back, 0, 1000);
}

std::vector<core::Vec2> GenerateTour(const TourConfig& config, std::uint64_t seed) {
  config.Validate();
  core::Rng rng(seed);
  Walker w(config);
  w.xs.push_back(0.0);
  for (int c = 0; c < config.columns; ++c)
    w.xs.push_back(w.xs.back() + rng.Uniform(config.block_size[0], config.block_size[1]));
  w.ys.push_back(0.0);
  for (int r = 0; r < config.rows; ++r)
    w.ys.push_back(w.ys.back() + rng.Uniform(config.block_size[0], config.block_size[1]));
  w.i = static_cast<int>(rng.UniformIndex(static_cast<std::uint64_t>(config.columns) + 1));
  w.j = static_cast<int>(rng.UniformIndex(static_cast<std::uint64_t>(config.rows) + 1));
  w.route.emplace_back(w.xs[w.i], w.ys[w.j]);

  int legs = config.out_and_back;
  while (w.length < config.length) {
    // A loop round a rectangle of blocks with a corner here, never starting with a U-turn.
    std::vector<std::vector<int>> laps;
    const int max_w = std::min(config.max_loop_blocks, config.columns);
    const int max_h = std::min(config.max_loop_blocks, config.rows);
    for (int first = 0; first < 4; ++first) {
      if (w.heading >= 0 && first == Reverse(w.heading)) continue;
      for (int turn : {1, -1}) {
        for (int bw = 1; bw <= max_w; ++bw) {
          for (int bh = 1; bh <= max_h; ++bh) {
            std::vector<int> lap = Walker::Lap(first, turn, bw, bh);
            if (w.Fits(lap)) laps.push_back(std::move(lap));
          }
        }
      }
    }
    if (!laps.empty()) {
      for (int d : laps[rng.UniformIndex(laps.size())]) {
        if (w.length >= config.length) break;
        w.Drive(d);
      }
    }
    if (legs > 0 && w.length < config.length) {
      --legs;
      w.OutAndBack(rng);
    }
    // Then on along one to max_transfer streets, never back the way it came.
    const int transfer =
        1 + static_cast<int>(rng.UniformIndex(static_cast<std::uint64_t>(config.max_transfer)));
    for (int k = 0; k < transfer && w.length < config.length; ++k) {
      const std::vector<int> ways = w.WaysOn();
      w.Drive(ways[rng.UniformIndex(ways.size())]);  // a grid crossing always has a way on
    }
  }
  return w.route;
}

}  // namespace retrace::bench
