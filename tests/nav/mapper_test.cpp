#include "nav/mapper.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "tests/support/config_key.hpp"
#include "tests/support/fake_scan.hpp"
#include "tests/support/reflect_coverage.hpp"

namespace retrace::nav {
namespace {

using core::Pose2;
using core::Vec2;
using retrace::testing::kValid;
using retrace::testing::ValidationErrorKey;

constexpr float kNoReturnF = std::numeric_limits<float>::infinity();

using testing::Rect;
using testing::ScanSpec;
using testing::Segment;

// A rectangular room with solid walls and solid boxes inside. Every coordinate lies 0.03 to
// 0.04 m from a multiple of 0.1 m, so that no face runs along a cell border of a 0.1 m grid
// whose origin is a multiple of 0.1 m (the mapper's grids are).
struct Room {
  Rect inside{-4.03, -3.07, 7.96, 5.04};  // the free interior; the walls are 0.2 m thick
  double wall = 0.2;
  std::vector<Rect> boxes{{0.53, 0.04, 1.54, 0.86}, {3.06, 1.47, 4.13, 2.36}};

  // The faces seen from inside: the walls' inner faces and every face of every box.
  std::vector<Segment> Faces() const {
    std::vector<Segment> faces;
    auto add_rect = [&](const Rect& r) {
      faces.push_back({{r.x0, r.y0}, {r.x1, r.y0}});
      faces.push_back({{r.x1, r.y0}, {r.x1, r.y1}});
      faces.push_back({{r.x1, r.y1}, {r.x0, r.y1}});
      faces.push_back({{r.x0, r.y1}, {r.x0, r.y0}});
    };
    add_rect(inside);
    for (const Rect& b : boxes) add_rect(b);
    return faces;
  }

  // The solid material: the wall ring and the boxes, as rectangles.
  std::vector<Rect> Solids() const {
    const Rect& i = inside;
    std::vector<Rect> solids{{i.x0 - wall, i.y0 - wall, i.x1 + wall, i.y0},
                             {i.x0 - wall, i.y1, i.x1 + wall, i.y1 + wall},
                             {i.x0 - wall, i.y0, i.x0, i.y1},
                             {i.x1, i.y0, i.x1 + wall, i.y1}};
    solids.insert(solids.end(), boxes.begin(), boxes.end());
    return solids;
  }
};

// An exactly ray-cast scan of `faces` from the LiDAR at X_WL, with Gaussian range noise
// σ = 0.01 m + 0.001 r (the simulated Hokuyo's) when rng is given.
core::LaserScan MakeScan(const std::vector<Segment>& faces, const Pose2& X_WL, const ScanSpec& spec,
                         core::Rng* rng) {
  std::function<double(double)> noise;
  if (rng != nullptr) {
    noise = [rng](double r) {
      return std::isfinite(r) ? r + rng->Normal(0.0, 0.01 + 0.001 * r) : r;
    };
  }
  return testing::FakeScan(
      spec, X_WL,
      [&](const Vec2& o, const Vec2& d) { return testing::NearestSegment(o, d, faces); }, noise);
}

// Poses of a loop around the boxes: straight legs in 0.05 m steps, turns on the spot in 1°
// steps at the corners.
std::vector<Pose2> LoopPoses() {
  const std::vector<Vec2> corners{{-2.0, -1.5}, {6.0, -1.5}, {6.0, 3.5}, {-2.0, 3.5}};
  std::vector<Pose2> poses;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const Vec2 a = corners[k];
    const Vec2 b = corners[(k + 1) % corners.size()];
    const double heading = std::atan2(b.y() - a.y(), b.x() - a.x());
    const int steps = static_cast<int>(std::round((b - a).norm() / 0.05));
    for (int s = 0; s < steps; ++s) {
      const Vec2 p = a + (b - a) * (static_cast<double>(s) / steps);
      poses.emplace_back(p.x(), p.y(), heading);
    }
    for (int deg = 0; deg < 90; ++deg) {
      poses.emplace_back(b.x(), b.y(), heading + core::DegToRad(deg));
    }
  }
  return poses;
}

bool SquareTouchesSegment(double x0, double y0, double x1, double y1, const Segment& s) {
  // Faces are axis-aligned: the closed square meets the segment iff their boxes overlap.
  const double sx0 = std::min(s.a.x(), s.b.x()), sx1 = std::max(s.a.x(), s.b.x());
  const double sy0 = std::min(s.a.y(), s.b.y()), sy1 = std::max(s.a.y(), s.b.y());
  return sx0 <= x1 && x0 <= sx1 && sy0 <= y1 && y0 <= sy1;
}

bool SquareOverlapsRect(double x0, double y0, double x1, double y1, const Rect& r) {
  return r.x0 < x1 && x0 < r.x1 && r.y0 < y1 && y0 < r.y1;  // interiors overlap
}

struct MapScore {
  double iou = 0.0;         // |P ∩ T| / |P ∪ T|
  double iou_banded = 0.0;  // the same with the solid band B left out of P
  int truth = 0, predicted = 0, hits = 0, band = 0;
  int free_side = 0;  // occupied cells neither in T nor in B: walls thickened into free space
  double recall() const { return static_cast<double>(hits) / truth; }
};

// Scores the occupied cells P (p > 0.65, what map_server calls occupied) of `grid` against the
// truth T: the cells whose closed square meets a face seen from inside. The banded score
// leaves out of P the cells of the band B: cells not in T that lie inside solid material
// (a wall or a box) and touch a cell of T. Those are occupied in reality, just not part of
// the visible surface; a noisy range marks them whenever the face lies within the noise of
// their border, and no beam can ever clear them. Cells marked on the free side of a face (a
// thickened wall that narrows a corridor) are errors in both scores.
MapScore Score(const core::OccupancyGrid& grid, const Room& room) {
  const std::vector<Segment> faces = room.Faces();
  const std::vector<Rect> solids = room.Solids();
  const int w = grid.width(), h = grid.height();
  const double res = grid.resolution();
  std::vector<char> truth(static_cast<std::size_t>(w) * h, 0);
  std::vector<char> solid(truth.size(), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double x0 = grid.origin().x() + x * res, y0 = grid.origin().y() + y * res;
      const std::size_t i = grid.Index({x, y});
      for (const Segment& s : faces)
        truth[i] |= SquareTouchesSegment(x0, y0, x0 + res, y0 + res, s);
      for (const Rect& r : solids) solid[i] |= SquareOverlapsRect(x0, y0, x0 + res, y0 + res, r);
    }
  }
  MapScore score;
  int union_all = 0, union_banded = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = grid.Index({x, y});
      bool near_truth = false;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const core::CellIndex n{x + dx, y + dy};
          near_truth |= grid.Contains(n) && truth[grid.Index(n)];
        }
      }
      const bool in_band = !truth[i] && solid[i] && near_truth;
      const bool p = grid.Probability({x, y}) > 0.65;
      score.truth += truth[i];
      score.predicted += p;
      score.hits += p && truth[i];
      score.band += p && in_band;
      union_all += p || truth[i];
      union_banded += (p && !in_band) || truth[i];
    }
  }
  score.free_side = score.predicted - score.hits - score.band;
  score.iou = static_cast<double>(score.hits) / union_all;
  score.iou_banded = static_cast<double>(score.hits) / union_banded;
  return score;
}

// A scan of `n` beams spread over `fov` (rad) around L's x axis, all reading `range`.
core::LaserScan UniformScan(int n, double fov, float range) {
  core::LaserScan scan;
  scan.angle_min = n > 1 ? -0.5 * fov : 0.0;
  scan.angle_increment = n > 1 ? fov / (n - 1) : 0.0;
  scan.range_min = 0.05;
  scan.range_max = 30.0;
  scan.ranges.assign(static_cast<std::size_t>(n), range);
  return scan;
}

std::vector<core::CellIndex> CellsWhere(const core::OccupancyGrid& grid, bool (*pred)(float)) {
  std::vector<core::CellIndex> cells;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      if (pred(grid.LogOdds({x, y}))) cells.push_back({x, y});
    }
  }
  return cells;
}

bool Positive(float l) { return l > 0.0f; }
bool Negative(float l) { return l < 0.0f; }
bool Touched(float l) { return l != 0.0f; }

TEST(Mapper, OneHitAndOneMissGiveTheModelsProbabilitiesFromUnknown) {
  Mapper mapper(MapperConfig{}, RobotGeometry{});
  mapper.SetPose(Pose2(0.05, 0.05, 0.0));  // the centre of a cell, beam along its row
  ASSERT_TRUE(mapper.OnScan(UniformScan(1, 0.0, 3.03f)));
  const core::OccupancyGrid& grid = mapper.grid();
  EXPECT_NEAR(grid.Probability(grid.WorldToCell({3.08, 0.05})), 0.94, 1e-6);
  EXPECT_NEAR(grid.Probability(grid.WorldToCell({1.55, 0.05})), 0.04, 1e-6);
  EXPECT_NEAR(grid.Probability(grid.WorldToCell({0.05, 0.05})), 0.04, 1e-6);
  EXPECT_EQ(grid.Probability(grid.WorldToCell({3.25, 0.05})), 0.5);  // behind: untouched
  EXPECT_EQ(grid.Probability(grid.WorldToCell({1.55, 0.15})), 0.5);  // beside: untouched
  EXPECT_EQ(mapper.stats().beams_hit, 1u);
}

TEST(Mapper, RepeatedHitsSaturateAtLogOddsMaxAndMissesAtLogOddsMin) {
  MapperConfig config;
  config.log_odds_min = -4.0;
  config.log_odds_max = 6.0;
  Mapper mapper(config, RobotGeometry{});
  const core::LaserScan scan = UniformScan(1, 0.0, 3.03f);
  for (int i = 0; i < 20; ++i) mapper.Integrate(scan, Pose2(0.05, 0.05, 0.0));
  const core::OccupancyGrid& grid = mapper.grid();
  EXPECT_FLOAT_EQ(grid.LogOdds(grid.WorldToCell({3.08, 0.05})), 6.0f);
  for (double x = 0.05; x < 2.9; x += 0.1) {
    EXPECT_FLOAT_EQ(grid.LogOdds(grid.WorldToCell({x, 0.05})), -4.0f) << "x " << x;
  }
  EXPECT_TRUE(mapper.path().empty());  // Integrate records no keyframe
}

TEST(Mapper, NoReturnBeamsClearUpToTheClearingRangeWithoutMarking) {
  MapperConfig config;
  config.no_return_range = 10.0;
  Mapper mapper(config, RobotGeometry{});
  mapper.SetPose(Pose2(0.05, 0.05, 0.0));
  ASSERT_TRUE(mapper.OnScan(UniformScan(181, core::DegToRad(180.0), kNoReturnF)));
  const core::OccupancyGrid& grid = mapper.grid();
  EXPECT_TRUE(CellsWhere(grid, Positive).empty());
  EXPECT_FALSE(CellsWhere(grid, Negative).empty());
  EXPECT_LT(grid.Probability(grid.WorldToCell({9.75, 0.05})), 0.05);  // inside 10 m: free
  EXPECT_EQ(grid.Probability(grid.WorldToCell({10.25, 0.05})), 0.5);  // beyond: unknown
  EXPECT_LT(grid.Probability(grid.WorldToCell({0.05, 9.75})), 0.05);
  EXPECT_EQ(mapper.stats().beams_cleared, 181u);
  EXPECT_EQ(mapper.stats().beams_hit, 0u);
  for (const core::CellIndex& c : CellsWhere(grid, Touched)) {
    EXPECT_LE((grid.CellToWorld(c) - Vec2(0.05, 0.05)).norm(), 10.0 + 0.08);
  }
}

// A Neato's LiDAR (range_max 5 m) reads +inf where nothing is within 5 m: that says nothing
// about 5 to 10 m, so its no-return beams clear to 5 m only, not to no_return_range.
TEST(Mapper, NoReturnBeamsClearNoFurtherThanTheScansOwnRangeMax) {
  MapperConfig config;
  config.no_return_range = 10.0;
  Mapper mapper(config, RobotGeometry{});
  mapper.SetPose(Pose2(0.05, 0.05, 0.0));
  core::LaserScan scan = UniformScan(361, core::DegToRad(360.0) * 360.0 / 361.0, kNoReturnF);
  scan.range_min = 0.2;
  scan.range_max = 5.0;
  ASSERT_TRUE(mapper.OnScan(scan));
  const core::OccupancyGrid& grid = mapper.grid();
  EXPECT_EQ(mapper.stats().beams_cleared, 361u);
  EXPECT_LT(grid.Probability(grid.WorldToCell({4.75, 0.05})), 0.05);  // inside 5 m: free
  EXPECT_EQ(grid.Probability(grid.WorldToCell({5.25, 0.05})), 0.5);   // beyond: unknown
  EXPECT_EQ(grid.Probability(grid.WorldToCell({0.05, -7.95})), 0.5);
  for (const core::CellIndex& c : CellsWhere(grid, Touched)) {
    EXPECT_LE((grid.CellToWorld(c) - Vec2(0.05, 0.05)).norm(), 5.0 + 0.08);
  }
}

// A flat wall at x = 3.03 m seen over 90 degrees, with every 7th beam a dropout (+inf).
core::LaserScan WallScanWithDropouts() {
  core::LaserScan scan = UniformScan(361, core::DegToRad(90.0), 0.0f);
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    scan.ranges[i] = i % 7 == 3 ? kNoReturnF : static_cast<float>(3.03 / std::cos(scan.Angle(i)));
  }
  return scan;
}

// Dropouts would otherwise paint free rays through a wall into the unknown behind it: in the
// scan that first sees the wall (they stop at its end points) and in later scans (they stop at
// cells the map holds as occupied).
TEST(Mapper, NoReturnBeamsStopAtTheWallsOfTheirOwnScanAndOfTheMap) {
  MapperConfig config;
  config.no_return_range = 10.0;
  config.keyframe_distance = 0.0;
  Mapper mapper(config, RobotGeometry{});
  mapper.SetPose(Pose2(0.05, 0.05, 0.0));
  ASSERT_TRUE(mapper.OnScan(WallScanWithDropouts()));
  EXPECT_EQ(mapper.stats().beams_cleared, 52u);
  const auto free_behind_the_wall = [&] {
    int n = 0;
    for (const core::CellIndex& c : CellsWhere(mapper.grid(), Negative)) {
      n += mapper.grid().CellToWorld(c).x() > 3.2 ? 1 : 0;
    }
    return n;
  };
  EXPECT_EQ(free_behind_the_wall(), 0);
  core::LaserScan all_dropouts = UniformScan(361, core::DegToRad(90.0), kNoReturnF);
  mapper.Integrate(all_dropouts, Pose2(0.05, 0.05, 0.0));
  EXPECT_EQ(free_behind_the_wall(), 0);
  EXPECT_FALSE(CellsWhere(mapper.grid(), Positive).empty());  // the wall is still there
}

TEST(Mapper, ReadingsBeyondTheLidarsRangeOnlyClear) {
  RobotGeometry robot;
  robot.range_max = 5.0;
  Mapper mapper(MapperConfig{}, robot);
  mapper.SetPose(Pose2(0.05, 0.05, 0.0));
  ASSERT_TRUE(mapper.OnScan(UniformScan(1, 0.0, 7.03f)));
  const core::OccupancyGrid& grid = mapper.grid();
  EXPECT_TRUE(CellsWhere(grid, Positive).empty());
  EXPECT_LT(grid.Probability(grid.WorldToCell({6.85, 0.05})), 0.05);
  EXPECT_EQ(grid.Probability(grid.WorldToCell({7.08, 0.05})), 0.5);
}

TEST(Mapper, InvalidBeamsAreSkipped) {
  Mapper mapper(MapperConfig{}, RobotGeometry{});
  core::LaserScan scan = UniformScan(4, core::DegToRad(90.0), 2.0f);
  scan.ranges = {-kNoReturnF, std::numeric_limits<float>::quiet_NaN(), 0.01f, 31.0f};
  ASSERT_TRUE(mapper.OnScan(scan));
  EXPECT_TRUE(CellsWhere(mapper.grid(), Touched).empty());
  EXPECT_EQ(mapper.stats().beams_skipped, 4u);
  EXPECT_EQ(mapper.path().size(), 1u);
}

TEST(Mapper, RayCastingVisitsEveryCellTheBeamCrossesExactlyOnce) {
  // A single beam from inside a cell; the cleared cells must form a 4-connected chain from the
  // sensor's cell to the end point's, with one cell per column or row crossing. No cells
  // behind the end point are updated (neighbourhood 0), so the chain ends in the end cell.
  MapperConfig config;
  config.inverse_model.neighbourhood_sigmas = 0.0;
  for (const double angle_deg : {0.0, 17.0, 45.0, 63.0, 90.0, 135.0, 200.0, 270.0, 333.0}) {
    Mapper mapper(config, RobotGeometry{});
    const Pose2 X_MR(0.237, -0.113, core::DegToRad(angle_deg));
    mapper.Integrate(UniformScan(1, 0.0, 4.0f), X_MR);
    const core::OccupancyGrid& grid = mapper.grid();
    const Vec2 start = X_MR.translation();
    const Vec2 end = X_MR * Vec2(4.0, 0.0);
    const core::CellIndex c0 = grid.WorldToCell(start);
    const core::CellIndex c1 = grid.WorldToCell(end);
    const std::vector<core::CellIndex> touched = CellsWhere(grid, Touched);
    EXPECT_EQ(static_cast<int>(touched.size()), std::abs(c1.x - c0.x) + std::abs(c1.y - c0.y) + 1)
        << angle_deg << " deg";
    EXPECT_GT(grid.LogOdds(c1), 0.0f) << angle_deg << " deg";
    EXPECT_LT(grid.LogOdds(c0), 0.0f) << angle_deg << " deg";
    for (const core::CellIndex& c : touched) {
      // Every touched cell's square is crossed by the segment (distance of its centre to the
      // line at most half a diagonal).
      const Vec2 p = grid.CellToWorld(c);
      const Vec2 d = (end - start).normalized();
      const Vec2 r = p - start;
      EXPECT_LE(std::abs(r.x() * d.y() - r.y() * d.x()), 0.5 * std::sqrt(2.0) * 0.1 + 1e-9);
    }
  }
}

TEST(Mapper, IntegratesOnlyAtKeyframes) {
  Mapper mapper(MapperConfig{}, RobotGeometry{});
  const core::LaserScan scan = UniformScan(91, core::DegToRad(270.0), 4.0f);
  EXPECT_TRUE(mapper.OnScan(scan));  // the first scan
  const std::vector<float> after_first = mapper.grid().log_odds();
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(mapper.OnScan(scan));  // standing still
  EXPECT_EQ(mapper.grid().log_odds(), after_first);
  mapper.SetPose(Pose2(0.49, 0.0, 0.0));
  EXPECT_FALSE(mapper.OnScan(scan));
  mapper.SetPose(Pose2(0.5, 0.0, 0.0));
  EXPECT_TRUE(mapper.OnScan(scan));
  mapper.SetPose(Pose2(0.5, 0.0, core::DegToRad(4.9)));
  EXPECT_FALSE(mapper.OnScan(scan));
  mapper.SetPose(Pose2(0.5, 0.0, core::DegToRad(5.0)));
  EXPECT_TRUE(mapper.OnScan(scan));
  mapper.SetPose(Pose2(0.5, 0.0, core::DegToRad(0.0)));  // turning back counts too
  EXPECT_TRUE(mapper.OnScan(scan));
  ASSERT_EQ(mapper.path().size(), 4u);
  EXPECT_EQ(mapper.path()[1], Pose2(0.5, 0.0, 0.0));
  EXPECT_EQ(mapper.path()[2], Pose2(0.5, 0.0, core::DegToRad(5.0)));
  EXPECT_EQ(mapper.stats().keyframes, 4u);
}

TEST(Mapper, GridGrowsWhenDrivingOutOfTheInitialArea) {
  MapperConfig config;
  config.initial_size = 10.0;
  Mapper mapper(config, RobotGeometry{});
  EXPECT_EQ(mapper.grid().width(), 100);
  EXPECT_EQ(mapper.grid().height(), 100);
  // A corridor: walls 2.03 m to either side, nothing ahead.
  core::LaserScan scan = UniformScan(181, core::DegToRad(180.0), kNoReturnF);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const double a = scan.Angle(i);
    if (std::abs(std::sin(a)) > 0.2)
      scan.ranges[i] = static_cast<float>(2.03 / std::abs(std::sin(a)));
  }
  for (double x = 0.0; x <= 60.0; x += 0.25) {
    mapper.SetPose(Pose2(x, 0.0, 0.0));
    mapper.OnScan(scan);
  }
  const core::OccupancyGrid& grid = mapper.grid();
  EXPECT_EQ(mapper.path().size(), 121u);
  EXPECT_GE(grid.origin().x() + grid.width() * grid.resolution(), 70.0);  // 60 m + 10 m clearing
  EXPECT_LE(grid.origin().x(), -5.0);
  // Walls both at the start (inside the initial area) and 55 m away are mapped.
  for (const double x : {1.05, 55.05}) {
    EXPECT_GT(grid.Probability(grid.WorldToCell({x, 2.05})), 0.9) << x;
    EXPECT_GT(grid.Probability(grid.WorldToCell({x, -2.05})), 0.9) << x;
    EXPECT_LT(grid.Probability(grid.WorldToCell({x, 0.05})), 0.1) << x;
  }
}

TEST(Mapper, ConfigErrorsNameTheKey) {
  EXPECT_EQ(ValidationErrorKey(MapperConfig{}), kValid);
  MapperConfig c;
  c.resolution = 0.0;
  EXPECT_EQ(ValidationErrorKey(c), "resolution");
  c = MapperConfig{};
  c.log_odds_max = -1.0;
  EXPECT_EQ(ValidationErrorKey(c), "log_odds_max");
  c = MapperConfig{};
  c.keyframe_distance = -0.1;
  EXPECT_EQ(ValidationErrorKey(c), "keyframe_distance");
  c = MapperConfig{};
  c.inverse_model.sigma = -0.01;
  EXPECT_EQ(ValidationErrorKey(c), "inverse_model.sigma");
  EXPECT_THROW(Mapper(c, RobotGeometry{}), core::ConfigError);
  RobotGeometry robot;
  robot.X_RL.x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ValidationErrorKey(robot), "X_RL");
  EXPECT_THROW(Mapper(MapperConfig{}, robot), core::ConfigError);
}

TEST(Mapper, ConfigReflectsEveryField) { EXPECT_EQ(testing::UnreflectedBytes<MapperConfig>(), ""); }

RobotGeometry RoomRobot() {
  RobotGeometry robot;
  robot.X_RL = Pose2(0.15, 0.05, 0.02);  // off-centre, to exercise X_RL
  return robot;
}

// Drives the loop with exact poses and noisy scans; returns the mapper.
Mapper MapRoom(const RobotGeometry& robot, const Room& room, std::uint64_t seed) {
  Mapper mapper(MapperConfig{}, robot);
  core::Rng rng(seed);
  const std::vector<Segment> faces = room.Faces();
  const Pose2 X_WM(-2.0, -1.5, 0.0);  // M starts at the loop's first pose
  for (const Pose2& X_WR : LoopPoses()) {
    const Pose2 X_MR = X_WM.Inverse() * X_WR;
    mapper.SetPose(X_MR);
    mapper.OnScan(MakeScan(faces, X_WR * robot.X_RL, ScanSpec{}, &rng));
  }
  return mapper;
}

// Shifts the room into M (the loop's first pose is M's origin, heading 0).
Room RoomInMap(const Room& room) {
  Room out = room;
  auto shift = [](Rect r) { return Rect{r.x0 + 2.0, r.y0 + 1.5, r.x1 + 2.0, r.y1 + 1.5}; };
  out.inside = shift(room.inside);
  for (Rect& b : out.boxes) b = shift(b);
  return out;
}

TEST(Mapper, ReproducesTheWallsOfAKnownRoomFromExactPoses) {
  const Room room;
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const Mapper mapper = MapRoom(RoomRobot(), room, seed);
    const MapScore score = Score(mapper.grid(), RoomInMap(room));
    std::printf(
        "[ mapper   ] seed %llu: banded IoU %.3f, IoU %.3f, recall %.3f; truth %d, "
        "occupied %d (on truth %d, solid band %d, free side %d), keyframes %zu\n",
        static_cast<unsigned long long>(seed), score.iou_banded, score.iou, score.recall(),
        score.truth, score.predicted, score.hits, score.band, score.free_side,
        mapper.stats().keyframes);
    EXPECT_GE(score.iou_banded, 0.9) << "seed " << seed;
    EXPECT_GE(score.recall(), 0.9) << "seed " << seed;
    EXPECT_LE(score.free_side, score.truth / 50) << "seed " << seed;
    // The strict IoU counts the marked solid band as errors (about 0.5 here: the band is
    // about as large as the surface); it guards against the band spreading further.
    EXPECT_GE(score.iou, 0.45) << "seed " << seed;
  }
}

}  // namespace
}  // namespace retrace::nav
