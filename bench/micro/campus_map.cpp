#include "bench/micro/campus_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "core/angle.hpp"

namespace retrace::bench_micro {

// Campus: building outlines, free-standing walls and trees on a free background.
core::OccupancyGrid CampusMap() {
  constexpr int kCells = kCampusCells;
  core::OccupancyGrid g(kCells, kCells, kCampusResolution, core::Vec2(-150.0, -150.0));
  const float free_l = static_cast<float>(core::Logit(0.05));
  const float occ_l = static_cast<float>(core::Logit(0.95));
  std::vector<float>& l = g.log_odds();
  std::fill(l.begin(), l.end(), free_l);
  const auto set = [&](int x, int y) {
    if (x >= 0 && y >= 0 && x < kCells && y < kCells)
      l[static_cast<std::size_t>(y) * kCells + x] = occ_l;
  };
  core::Rng rng(2018);
  for (int b = 0; b < 70; ++b) {  // buildings: 3-cell-thick outlines with a door gap
    const int x0 = static_cast<int>(rng.UniformIndex(kCells - 400)) + 50;
    const int y0 = static_cast<int>(rng.UniformIndex(kCells - 400)) + 50;
    const int w = 100 + static_cast<int>(rng.UniformIndex(300)),
              h = 100 + static_cast<int>(rng.UniformIndex(300));
    for (int t = 0; t < 3; ++t) {
      for (int x = x0; x <= x0 + w; ++x) {
        if (x - x0 > 20 && x - x0 < 40) continue;
        set(x, y0 + t);
        set(x, y0 + h - t);
      }
      for (int y = y0; y <= y0 + h; ++y) {
        set(x0 + t, y);
        set(x0 + w - t, y);
      }
    }
  }
  for (int k = 0; k < 120; ++k) {  // walls and hedges: 2 cells thick, 5-30 m long
    const double x = rng.Uniform(0, kCells), y = rng.Uniform(0, kCells);
    const double a = rng.Uniform(0, 2 * std::numbers::pi), len = rng.Uniform(50, 300);
    for (double s = 0; s < len; s += 0.5) {
      set(static_cast<int>(x + s * std::cos(a)), static_cast<int>(y + s * std::sin(a)));
      set(static_cast<int>(x + s * std::cos(a)) + 1, static_cast<int>(y + s * std::sin(a)));
    }
  }
  for (int k = 0; k < 3000; ++k) {  // trees: discs of radius 2-4 cells
    const int cx = static_cast<int>(rng.UniformIndex(kCells)),
              cy = static_cast<int>(rng.UniformIndex(kCells));
    const int r = 2 + static_cast<int>(rng.UniformIndex(3));
    for (int y = -r; y <= r; ++y) {
      for (int x = -r; x <= r; ++x) {
        if (x * x + y * y <= r * r) set(cx + x, cy + y);
      }
    }
  }
  return g;
}

core::Pose2 FreeCampusPose(const core::OccupancyGrid& map, const nav::LikelihoodField& field,
                           core::Rng& rng) {
  while (true) {
    const core::Pose2 X(rng.Uniform(-50, 50), rng.Uniform(-50, 50), rng.Uniform(-3, 3));
    if (field.Distance(map.WorldToCell(X.translation())) > 1.5f) return X;
  }
}

core::LaserScan CampusScan(const nav::GridRayCaster& caster, const core::Pose2& X_M,
                           core::Rng& rng) {
  core::LaserScan scan;
  scan.angle_min = -core::DegToRad(135.0);
  scan.angle_increment = core::DegToRad(0.25);
  scan.range_min = 0.05;
  scan.range_max = 30.0;
  for (std::size_t i = 0; i < 1081; ++i) {
    const double a = X_M.theta + scan.Angle(i);
    const double r = caster.Cast(X_M.x, X_M.y, std::cos(a), std::sin(a), 30.0);
    scan.ranges.push_back(std::isinf(r) ? static_cast<float>(r)
                                        : static_cast<float>(r + 0.02 * rng.Normal()));
  }
  return scan;
}

CampusDrive DriveThroughCampus(int keyframes, double turn, std::uint64_t seed) {
  const core::OccupancyGrid map = CampusMap();
  const nav::LikelihoodField field(map, {}, 30.0);
  const nav::GridRayCaster caster(field);
  core::Rng rng(seed);
  core::Pose2 X = FreeCampusPose(map, field, rng);
  CampusDrive drive;
  while (static_cast<int>(drive.poses.size()) < keyframes) {
    const double ahead = caster.Cast(X.x, X.y, std::cos(X.theta), std::sin(X.theta), 30.0);
    if (ahead < 2.0) {
      X = core::Pose2(X.x, X.y, X.theta + 0.6);
      continue;
    }
    drive.poses.push_back(X);
    drive.scans.push_back(CampusScan(caster, X, rng));
    X = X * core::Pose2(0.5, 0.0, turn);
  }
  return drive;
}

}  // namespace retrace::bench_micro
