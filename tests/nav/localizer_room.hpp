#pragma once
// The localizer tests' world: a 12 m x 9 m furnished room, its map, a robot driving circles in it
// with the simulator's odometry error model, fake scans with walkers in the way, and a loop that
// localizes along the drive.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "nav/localizer.hpp"
#include "tests/support/config_key.hpp"
#include "tests/support/fake_scan.hpp"

namespace retrace::nav::testing_room {

using core::Pose2;
using core::Vec2;
using retrace::testing::kValid;
using retrace::testing::ValidationErrorKey;

constexpr double kInfD = std::numeric_limits<double>::infinity();

using testing::Circle;
using testing::Rect;

// A 12 m x 9 m room with 0.2 m walls and asymmetric furniture.
inline std::vector<Rect> RoomGeometry() {
  return {{0, 0, 12, 0.2},  {0, 8.8, 12, 9},       {0, 0, 0.2, 9},       {11.8, 0, 12, 9},
          {2, 6, 3.5, 7},   {8.3, 1.0, 9.3, 1.8},  {5.0, 4.0, 5.6, 4.6}, {9.5, 6, 10.5, 6.4},
          {1, 1, 1.6, 2.5}, {10.6, 3.5, 11.8, 3.8}};
}

// Rasterises rectangles at 0.1 m: a cell is occupied (0.95) when its centre lies in one, free
// (0.05) otherwise.
inline core::OccupancyGrid Rasterise(const std::vector<Rect>& rects) {
  core::OccupancyGrid g(140, 110, 0.1, Vec2(-1.0, -1.0));
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const Vec2 c = g.CellToWorld({x, y});
      bool occ = false;
      for (const Rect& r : rects) {
        occ = occ || (c.x() >= r.x0 && c.x() <= r.x1 && c.y() >= r.y0 && c.y() <= r.y1);
      }
      g.SetProbability({x, y}, occ ? 0.95 : 0.05);
    }
  }
  return g;
}

// A scan like the simulated Hokuyo (270°, 1081 beams, 0.05-30 m) from X_WL, cast against the
// exact rectangles and the unmapped circles, Gaussian noise σ = 0.01 + 0.001 r. blocked[i] says
// whether beam i truly hit a circle first.
inline core::LaserScan MakeScan(const std::vector<Rect>& rects, const std::vector<Circle>& circles,
                                const Pose2& X_WL, core::Rng& rng,
                                std::vector<bool>* blocked = nullptr) {
  if (blocked != nullptr) blocked->clear();
  const auto cast = [&](const Vec2& o, const Vec2& d) {
    double t_static = kInfD, t_dyn = kInfD;
    for (const Rect& r : rects) t_static = std::min(t_static, testing::RayRect(o, d, r));
    for (const Circle& c : circles) t_dyn = std::min(t_dyn, testing::RayCircle(o, d, c));
    if (blocked != nullptr) blocked->push_back(t_dyn < t_static);
    return std::min(t_static, t_dyn);
  };
  return testing::FakeScan(testing::ScanSpec{}, X_WL, cast,
                           [&](double t) { return t + (0.01 + 0.001 * t) * rng.Normal(); });
}

inline LocalizerConfig TestConfig() { return LocalizerConfig{}; }

inline RobotGeometry TestRobot() {
  RobotGeometry robot;
  robot.X_RL = Pose2(0.2, 0.0, 0.0);
  return robot;
}

// The robot drives a circle of radius 2.5 m around the room centre, counter-clockwise, at
// 0.025 m per odometry tick; odometry readings carry the simulator's error model (1 % scale,
// α noise). A scan comes every second tick.
struct Drive {
  std::vector<Rect> rects = RoomGeometry();
  core::OccupancyGrid map = Rasterise(rects);
  Pose2 X_WR{6.0, 2.0, 0.0};
  core::Rng rng;
  explicit Drive(std::uint64_t seed) : rng(core::Rng(seed).Split("world")) {}

  core::OdometryDelta Step() {
    const core::OdometryDelta truth{0.025, 0.025 / 2.5};
    X_WR = core::IntegrateOdometry(X_WR, truth);
    core::OdometryDelta measured;
    measured.distance = 1.01 * truth.distance + std::sqrt(1e-3 * truth.distance) * rng.Normal();
    measured.dtheta =
        1.01 * truth.dtheta +
        std::sqrt(2e-4 * std::abs(truth.dtheta) + 1e-5 * truth.distance) * rng.Normal();
    return measured;
  }
  // Pedestrian-sized unmapped circles walking with the robot 1.4-1.6 m away, spread over the
  // field of view and blocking over 30 % of the tested beams (36.5 % measured).
  std::vector<Circle> Walkers() const {
    std::vector<Circle> out;
    for (const double bearing_deg : {-95.0, -35.0, 25.0, 85.0}) {
      const double b = X_WR.theta + core::DegToRad(bearing_deg);
      const double dist = bearing_deg < 0.0 ? 1.4 : 1.6;
      out.push_back({X_WR.translation() + dist * Vec2(std::cos(b), std::sin(b)), 0.3});
    }
    return out;
  }
};

inline double PositionError(const Pose2& a, const Pose2& b) { return core::Distance(a, b); }
inline double HeadingError(const Pose2& a, const Pose2& b) {
  return std::abs(core::AngleDiff(a.theta, b.theta));
}

// Drives until `updates` measurement updates have run; returns the final errors.
struct RunResult {
  double final_position_error = 0.0;
  double final_heading_error = 0.0;
  double mean_position_error = 0.0;  // over updates after the first `skip`
  int updates = 0;
  int tp = 0, fp = 0, fn = 0;
  int tested = 0;  // beams tested for rejection
  int trials = 0;        // updates with a recovery trial running
  int reacquisitions = 0;  // trials that replaced the belief
};

inline RunResult DriveAndLocalize(Localizer& loc, Drive& drive, int updates, bool walkers,
                                  int skip = 0) {
  RunResult res;
  double sum = 0.0;
  int counted = 0;
  for (int tick = 0; res.updates < updates && tick < 100000; ++tick) {
    loc.Predict(drive.Step());
    if (tick % 2 != 0) continue;
    std::vector<bool> blocked;
    const Pose2 X_WL = drive.X_WR * TestRobot().X_RL;
    const core::LaserScan scan = MakeScan(
        drive.rects, walkers ? drive.Walkers() : std::vector<Circle>{}, X_WL, drive.rng, &blocked);
    const LocalizerUpdate u = loc.Update(scan);
    if (!u.ran) continue;
    ++res.updates;
    res.trials += u.trial_updates > 0 ? 1 : 0;
    res.reacquisitions += u.reacquired ? 1 : 0;
    for (std::size_t i = 0; i < u.beams.size(); ++i) {
      if (u.beams[i] == BeamUse::kUnused) continue;
      const bool rejected = u.beams[i] == BeamUse::kRejected;
      ++res.tested;
      res.tp += rejected && blocked[i];
      res.fp += rejected && !blocked[i];
      res.fn += !rejected && blocked[i];
    }
    if (res.updates > skip) {
      sum += PositionError(loc.Estimate(), drive.X_WR);
      ++counted;
    }
  }
  res.final_position_error = PositionError(loc.Estimate(), drive.X_WR);
  res.final_heading_error = HeadingError(loc.Estimate(), drive.X_WR);
  res.mean_position_error = counted > 0 ? sum / counted : 0.0;
  return res;
}

// Initial estimate 0.5 m and 10° off the truth, in a seed-dependent direction.
inline Pose2 Perturbed(const Pose2& truth, std::uint64_t seed) {
  core::Rng r(seed * 7919 + 1);
  const double dir = r.Uniform(-core::kPi, core::kPi);
  const double sign = r.Bernoulli(0.5) ? 1.0 : -1.0;
  return {truth.x + 0.5 * std::cos(dir), truth.y + 0.5 * std::sin(dir),
          truth.theta + sign * core::DegToRad(10.0)};
}

}  // namespace retrace::nav::testing_room
