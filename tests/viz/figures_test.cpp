// Each figure on small synthetic data: the file exists with the expected size, is not blank,
// has the right colours where known world points fall, is byte-identical when rendered twice,
// and a bad output path or missing data gives core::IoError.

#include "viz/figures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <type_traits>

#include "core/errors.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/viz/viz_test_data.hpp"
#include "viz/render_error.hpp"
#include "viz/style.hpp"

namespace retrace::viz {
namespace {

using testing::ColorNear;
using testing::DistinctColors;
using testing::PixelAt;

class FiguresTest : public retrace::testing::TempDirTest {
 protected:
  // Checks what every figure must satisfy and returns the image.
  Image CheckFile(const FigureInfo& info, int width) {
    EXPECT_TRUE(std::filesystem::exists(info.path));
    const Image img = ReadPng(info.path);
    EXPECT_EQ(img.width, width);
    EXPECT_EQ(img.width, info.width);
    EXPECT_EQ(img.height, info.height);
    EXPECT_GT(img.height, 200);
    EXPECT_GT(DistinctColors(img), 20u);
    return img;
  }

  std::string Bytes(const FigureInfo& info) { return tmp_.Read(info.path); }

  std::filesystem::path BadPath() {
    tmp_.Write("not_a_folder", "x");
    return tmp_.path() / "not_a_folder" / "fig.png";
  }
};

MapsFigureData SmallMaps() {
  MapsFigureData d;
  d.world = testing::SmallWorld();
  d.route = testing::SmallRoute();
  // Two maps: the route split at (37, 4); each map's frame starts at its segment's start.
  const core::Pose2 X_WM0(3, 4, 0.0);
  const core::Pose2 X_WM1(37, 4, core::kPi / 2);
  for (const core::Pose2& X_WM : {X_WM0, X_WM1}) {
    PartialMapView m;
    m.grid = testing::SmallGrid();
    m.X_WM = X_WM;
    m.path = testing::Densify({{0, 0}, {14, 0}}, 0.5);
    m.switch_pose = core::Pose2(14, 0, 0);
    d.maps.push_back(m);
  }
  d.maps.back().switch_pose.reset();
  d.switch_poses.push_back(core::Pose2(37, 4, core::kPi / 2));
  return d;
}

TEST_F(FiguresTest, MapsFigureShowsRouteWorldAndEachMap) {
  const MapsFigureData d = SmallMaps();
  const FigureInfo info = RenderMapsFigure(d, tmp_.path() / "maps.png");
  const Image img = CheckFile(info, 1600);
  const PanelInfo& world = info.Panel("world");
  // Inside the building, on the first (map 0) and last (map 1) part of the route.
  EXPECT_TRUE(ColorNear(PixelAt(img, world, Vec2(15, 14)), palette::kWorldSolid, 6));
  EXPECT_TRUE(ColorNear(PixelAt(img, world, Vec2(20, 4)), MapColor(0)));
  EXPECT_TRUE(ColorNear(PixelAt(img, world, Vec2(37, 15)), MapColor(1)));
  EXPECT_TRUE(ColorNear(PixelAt(img, world, Vec2(20, 6)), palette::kBackground, 6));
  // Map 0 in its own frame: the path along y = 0, free space, the wall at y = 8 m.
  const PanelInfo& m0 = info.Panel("map0");
  EXPECT_TRUE(ColorNear(PixelAt(img, m0, Vec2(7, 0)), MapColor(0)));
  EXPECT_TRUE(ColorNear(PixelAt(img, m0, Vec2(7, 4)), palette::kMapFree, 6));
  EXPECT_TRUE(ColorNear(PixelAt(img, m0, Vec2(7, 8.05)), palette::kMapOccupied, 100));
  EXPECT_TRUE(ColorNear(PixelAt(img, m0, Vec2(16.5, 4)), palette::kMapUnknown, 6));
  EXPECT_TRUE(ColorNear(PixelAt(img, info.Panel("map1"), Vec2(7, 0)), MapColor(1)));
  // The switch marker (gold) at the end of map 0's path.
  EXPECT_TRUE(ColorNear(PixelAt(img, m0, Vec2(14, 0)), palette::kSwitch));
  EXPECT_EQ(Bytes(info), Bytes(RenderMapsFigure(d, tmp_.path() / "maps2.png")));
}

// A log's teaching drive without a reference: the route is its odometry, and there is no world
// whose buildings and trees the legend would explain.
TEST_F(FiguresTest, MapsFigureOfALogWithoutReferenceIsTitledOdometryWithoutWorldLegend) {
  MapsFigureData d = SmallMaps();
  const FigureInfo sim = RenderMapsFigure(d, tmp_.path() / "sim.png");
  EXPECT_EQ(sim.Panel("world").title, "Ground truth in the world frame W");
  EXPECT_NE(std::find(sim.legend.begin(), sim.legend.end(), "buildings, walls, trees"),
            sim.legend.end());

  d.world = {};
  d.route_source = RouteSource::kOdometry;
  const FigureInfo log = RenderMapsFigure(d, tmp_.path() / "log.png");
  EXPECT_EQ(log.Panel("world").title, "Odometry (no reference) in the odometry frame O");
  for (const std::string& label : log.legend) {
    EXPECT_EQ(label.find("buildings"), std::string::npos) << label;
    EXPECT_EQ(label.find("trees"), std::string::npos) << label;
  }
  EXPECT_NE(std::find(log.legend.begin(), log.legend.end(), "map 0 path"), log.legend.end());
  d.route_source = RouteSource::kReference;
  EXPECT_EQ(RenderMapsFigure(d, tmp_.path() / "ref.png").Panel("world").title,
            "Reference trajectory in the world frame W");
}

TEST_F(FiguresTest, MapsFigureNeedsMapsAndAWritablePath) {
  MapsFigureData d = SmallMaps();
  EXPECT_THROW(RenderMapsFigure(d, BadPath()), core::IoError);
  d.maps.clear();
  EXPECT_THROW(RenderMapsFigure(d, tmp_.path() / "m.png"), core::IoError);
  EXPECT_FALSE(std::filesystem::exists(tmp_.path() / "m.png"));
}

TEST_F(FiguresTest, MapsCompareFigureShowsBothMaps) {
  const MapsFigureData maps = SmallMaps();
  MapsCompareFigureData d;
  d.maps = maps.maps;
  d.maps[0].label = "consistent";
  d.maps[1].label = "single";
  const FigureInfo info =
      RenderMapsCompareFigure(d, tmp_.path() / "maps_compare.png", {1200, 2, ""});
  const Image img = CheckFile(info, 1200);
  EXPECT_TRUE(ColorNear(PixelAt(img, info.Panel("map0"), Vec2(7, 0)), palette::kTaughtPath));
  EXPECT_TRUE(ColorNear(PixelAt(img, info.Panel("map1"), Vec2(7, 4)), palette::kMapFree, 6));
  EXPECT_GT(info.Panel("map1").x, info.Panel("map0").x);
  EXPECT_THROW(RenderMapsCompareFigure(d, BadPath()), core::IoError);
}

PlaybackFigureData SmallPlayback() {
  PlaybackFigureData d;
  d.mode = "partial";
  d.world = testing::SmallWorld();
  d.target = testing::SmallRoute();
  // Three runs offset sideways; they spread most around x = 20 on the first leg.
  for (int r = 0; r < 3; ++r) {
    Trajectory t;
    for (const auto& p : d.target) {
      const double bump = p.y < 5.0 ? 0.6 * std::exp(-std::pow((p.x - 20.0) / 2.0, 2)) : 0.0;
      const double off = 0.1 * (r - 1) + bump * (r - 1);
      t.poses.emplace_back(p.x - off * std::sin(p.theta), p.y + off * std::cos(p.theta), p.theta);
    }
    d.runs.push_back(t);
  }
  d.switch_poses.push_back(core::Pose2(37, 4, 0));
  return d;
}

TEST_F(FiguresTest, PlaybackFigureDrawsRunsOverTheWorldWithAnInsetWhereTheySpread) {
  const PlaybackFigureData d = SmallPlayback();
  const FigureInfo info = RenderPlaybackFigure(d, tmp_.path() / "playback_partial.png");
  const Image img = CheckFile(info, 1600);
  const PanelInfo& world = info.Panel("world");
  const PanelInfo& inset = info.Panel("inset");
  EXPECT_TRUE(ColorNear(PixelAt(img, world, Vec2(15, 14)), palette::kWorldSolid, 6));
  // The inset is centred where the runs spread most (x = 20 on the first leg).
  EXPECT_NEAR(inset.box.Center().x(), 20.0, 0.6);
  EXPECT_NEAR(inset.box.Center().y(), 4.0, 0.6);
  // Zoomed so that 0.1 m is at least 3 px.
  EXPECT_GE(inset.width / inset.box.Size().x(), 30.0);
  // Run 2 is 0.7 m left of the target at x = 20 and run 0 as far right; the target between.
  EXPECT_TRUE(ColorNear(PixelAt(img, inset, Vec2(20, 4.7)), RunColor(2), 60));
  EXPECT_TRUE(ColorNear(PixelAt(img, inset, Vec2(20, 3.3)), RunColor(0), 60));
  EXPECT_TRUE(ColorNear(PixelAt(img, inset, Vec2(20, 4.35)), palette::kBackground, 6));
  // Runs 1 (on the target) covers the target in the middle.
  EXPECT_TRUE(ColorNear(PixelAt(img, inset, Vec2(20, 4.0)), RunColor(1), 60));
  EXPECT_EQ(Bytes(info), Bytes(RenderPlaybackFigure(d, tmp_.path() / "p2.png")));
  EXPECT_THROW(RenderPlaybackFigure(d, BadPath()), core::IoError);
}

TEST_F(FiguresTest, PlaybackInsetCanBePlacedByTheCaller) {
  PlaybackFigureOptions o;
  o.inset_center = Vec2(37, 20);
  o.inset_size = 6.0;
  const FigureInfo info = RenderPlaybackFigure(SmallPlayback(), tmp_.path() / "p.png", o);
  EXPECT_NEAR(info.Panel("inset").box.Center().x(), 37.0, 1e-6);
  EXPECT_NEAR(info.Panel("inset").box.Center().y(), 20.0, 1e-6);
}

TEST_F(FiguresTest, OdometryFigureAlignsOdometryAtTheStart) {
  OdometryFigureData d;
  d.world = testing::SmallWorld();
  OdometryDrive drive;
  drive.label = "teaching";
  drive.truth = testing::SmallRoute();
  // Odometry in its own frame: starts at (100, 50) facing +y, drifts 10% long.
  const core::Pose2 X_OW = core::Pose2(100, 50, core::kPi / 2) * drive.truth.front().Inverse();
  for (const auto& X_WR : drive.truth) {
    core::Pose2 X_OR = X_OW * X_WR;
    X_OR = core::Pose2(100 + 1.1 * (X_OR.x - 100), 50 + 1.1 * (X_OR.y - 50), X_OR.theta);
    drive.odometry.push_back(X_OR);
  }
  d.drives = {drive, drive};
  d.drives[1].label = "playback run 0";
  const FigureInfo info = RenderOdometryFigure(d, tmp_.path() / "odometry.png");
  const Image img = CheckFile(info, 1600);
  const PanelInfo& p = info.Panel("drive0");
  // Truth along y = 4; odometry along the same heading but 10% longer: at x = 3 + 1.1 * 34.
  EXPECT_TRUE(ColorNear(PixelAt(img, p, Vec2(20, 4)), palette::kTruth, 60) ||
              ColorNear(PixelAt(img, p, Vec2(20, 4)), palette::kOdometry, 60));
  EXPECT_TRUE(ColorNear(PixelAt(img, p, Vec2(37, 15)), palette::kTruth));
  EXPECT_TRUE(ColorNear(PixelAt(img, p, Vec2(3 + 1.1 * 34, 15)), palette::kOdometry));
  EXPECT_TRUE(ColorNear(PixelAt(img, info.Panel("drive1"), Vec2(37, 15)), palette::kTruth));
  EXPECT_EQ(Bytes(info), Bytes(RenderOdometryFigure(d, tmp_.path() / "o2.png")));
  EXPECT_THROW(RenderOdometryFigure(d, BadPath()), core::IoError);
  EXPECT_THROW(RenderOdometryFigure({}, tmp_.path() / "o3.png"), core::IoError);
}

LikelihoodFigureData SmallLikelihood() {
  LikelihoodFigureData d;
  d.true_pose = core::Pose2(1.0, 1.0, 0.0);
  d.pedestrians = {{Vec2(1.8, 1.5), 0.3}};
  for (int k = 0; k < 2; ++k) {
    LikelihoodGrid& g = k == 0 ? d.without_rejection : d.with_rejection;
    g.width = 40;
    g.height = 40;
    g.resolution = 0.05;
    g.origin = Vec2(0, 0);
    // Peak at (1.5, 1.5) without rejection, at the true pose with it.
    const Vec2 peak = k == 0 ? Vec2(1.5, 1.5) : Vec2(1.0, 1.0);
    for (int y = 0; y < 40; ++y) {
      for (int x = 0; x < 40; ++x) {
        const Vec2 p((x + 0.5) * 0.05, (y + 0.5) * 0.05);
        g.values.push_back(-20.0 * (p - peak).squaredNorm());
      }
    }
  }
  return d;
}

TEST_F(FiguresTest, LikelihoodFigureColoursPeaksBrightAndFarCellsDark) {
  const LikelihoodFigureData d = SmallLikelihood();
  LikelihoodFigureOptions linear;
  linear.log_scale = false;
  const FigureInfo info = RenderLikelihoodFigure(d, tmp_.path() / "likelihood.png", linear);
  const Image img = CheckFile(info, 1600);
  const PanelInfo& without = info.Panel("without");
  const PanelInfo& with = info.Panel("with");
  // Viridis: bright yellow at the maximum, dark purple far from it.
  const Rgba yellow{253, 231, 37};
  const Rgba purple{68, 1, 84};
  EXPECT_TRUE(ColorNear(PixelAt(img, without, Vec2(1.52, 1.52)), yellow, 60));
  EXPECT_TRUE(ColorNear(PixelAt(img, without, Vec2(0.1, 0.1)), purple, 10));
  EXPECT_TRUE(ColorNear(PixelAt(img, with, Vec2(1.7, 1.7)), purple, 10));
  // The true pose's arrow (green) in both panels.
  EXPECT_TRUE(ColorNear(PixelAt(img, without, Vec2(1.02, 1.0)), palette::kTruth, 60));
  EXPECT_TRUE(ColorNear(PixelAt(img, with, Vec2(1.02, 1.0)), palette::kTruth, 60));
  EXPECT_EQ(Bytes(info), Bytes(RenderLikelihoodFigure(d, tmp_.path() / "l2.png", linear)));
  EXPECT_THROW(RenderLikelihoodFigure(d, BadPath()), core::IoError);
  LikelihoodFigureData bad = d;
  bad.with_rejection.values.pop_back();
  EXPECT_THROW(RenderLikelihoodFigure(bad, tmp_.path() / "l3.png"), core::IoError);
}

TEST_F(FiguresTest, LikelihoodFigureAcceptsPlainLikelihoodsOnALogScale) {
  LikelihoodFigureData d = SmallLikelihood();
  for (auto* g : {&d.without_rejection, &d.with_rejection}) {
    for (double& v : g->values) v = std::exp(v);
    g->log_values = false;
  }
  // Log scale: bright at the peak, dark where the log-likelihood is more than log_range below
  // it (the corner: -20 * 1.62 = -32).
  LikelihoodFigureOptions o;
  o.log_range = 20.0;
  const FigureInfo info = RenderLikelihoodFigure(d, tmp_.path() / "l.png", o);
  const Image img = CheckFile(info, 1600);
  EXPECT_TRUE(ColorNear(PixelAt(img, info.Panel("with"), Vec2(1.1, 1.1)), {253, 231, 37}, 60));
  EXPECT_TRUE(ColorNear(PixelAt(img, info.Panel("with"), Vec2(1.9, 0.1)), {68, 1, 84}, 10));
}

TEST_F(FiguresTest, SnapshotFigureColoursScanPointsByClass) {
  SnapshotData d;
  d.robot_radius = 0.3;
  d.time_s = 12.5;
  d.map_index = 1;
  d.grid = testing::SmallGrid();
  d.truth = core::Pose2(3.0, 2.0, 0.0);
  d.estimate = core::Pose2(3.1, 2.05, 0.02);
  for (int i = 0; i < 50; ++i) {
    d.particles.push_back(d.estimate * core::Pose2(0.01 * (i % 7 - 3), 0.01 * (i % 5 - 2), 0.0));
    d.weights.push_back(1.0 + i % 3);
  }
  for (double x = 0.0; x <= 10.0; x += 0.5) d.scan.push_back({Vec2(x, 8.05), false, false});
  d.scan.push_back({Vec2(6.0, 4.0), true, true});   // a pedestrian, rejected
  d.scan.push_back({Vec2(8.0, 4.0), true, false});  // rejected, but static
  d.pedestrians = {{Vec2(6.2, 4.0), 0.3}};
  const FigureInfo info = RenderSnapshotFigure(d, tmp_.path() / "snapshot.png");
  const Image img = CheckFile(info, 1600);
  const PanelInfo& map = info.Panel("map");
  EXPECT_TRUE(ColorNear(PixelAt(img, map, Vec2(2.0, 8.05)), palette::kStaticPoint, 50));
  EXPECT_TRUE(ColorNear(PixelAt(img, map, Vec2(8.0, 4.0)), palette::kRejectedPoint, 50));
  EXPECT_TRUE(ColorNear(PixelAt(img, map, Vec2(6.0, 4.0)), palette::kRejectedPoint, 50));
  EXPECT_TRUE(ColorNear(PixelAt(img, map, Vec2(1.0, 5.0)), palette::kMapFree, 6));
  // The inset is zoomed on the particles, estimate and truth.
  const PanelInfo& inset = info.Panel("inset");
  EXPECT_TRUE(inset.box.Contains(Vec2(3.0, 2.0)));
  EXPECT_TRUE(inset.box.Contains(Vec2(3.1, 2.05)));
  EXPECT_LT(inset.box.Size().x(), 5.0);
  EXPECT_TRUE(ColorNear(PixelAt(img, inset, Vec2(3.1 + 0.05, 2.05)), palette::kEstimate, 60));
  EXPECT_EQ(Bytes(info), Bytes(RenderSnapshotFigure(d, tmp_.path() / "s2.png")));
  EXPECT_THROW(RenderSnapshotFigure(d, BadPath()), core::IoError);
}

TEST_F(FiguresTest, ErrorsFigurePlotsEachRunAgainstArcLength) {
  ErrorsFigureData d;
  d.mode = "partial";
  for (int r = 0; r < 2; ++r) {
    ErrorSeries s;
    for (int i = 0; i <= 1000; ++i) {
      s.arc_length.push_back(0.1 * i);
      s.tracking_error.push_back(r == 0 ? 0.2 : 0.6);
      s.localization_error.push_back(i < 500 ? 0.1 : std::nan(""));
    }
    d.runs.push_back(s);
  }
  d.switch_arc_lengths = {50.0};
  const FigureInfo info = RenderErrorsFigure(d, tmp_.path() / "errors.png");
  const Image img = CheckFile(info, 1600);
  const PanelInfo& tracking = info.Panel("tracking");
  const PanelInfo& localization = info.Panel("localization");
  EXPECT_NEAR(tracking.box.max.x(), 100.0, 1e-9);
  EXPECT_TRUE(ColorNear(PixelAt(img, tracking, Vec2(30, 0.2)), RunColor(0), 60));
  EXPECT_TRUE(ColorNear(PixelAt(img, tracking, Vec2(30, 0.6)), RunColor(1), 60));
  EXPECT_TRUE(ColorNear(PixelAt(img, tracking, Vec2(30, 0.4)), palette::kBackground, 40));
  EXPECT_TRUE(ColorNear(PixelAt(img, localization, Vec2(20, 0.1)), RunColor(1), 60));
  // No line where the localization error is NaN.
  EXPECT_FALSE(ColorNear(PixelAt(img, localization, Vec2(80, 0.1)), RunColor(1), 60));
  // The switch line.
  EXPECT_TRUE(ColorNear(PixelAt(img, tracking, Vec2(50, 0.02)), palette::kSwitch, 60) ||
              ColorNear(PixelAt(img, tracking, Vec2(50, 0.05)), palette::kSwitch, 60));
  EXPECT_EQ(Bytes(info), Bytes(RenderErrorsFigure(d, tmp_.path() / "e2.png")));
  EXPECT_THROW(RenderErrorsFigure(d, BadPath()), core::IoError);
  EXPECT_THROW(RenderErrorsFigure({}, tmp_.path() / "e3.png"), core::IoError);
}

TEST_F(FiguresTest, ComparisonFigureDrawsABarPerModeAndMetric) {
  ComparisonFigureData d;
  d.scenario = "small";
  for (const char* mode : {"partial", "single", "consistent"}) {
    ModeMetrics m;
    m.mode = mode;
    const double base = m.mode == "single" ? 0.5 : 0.2;
    m.metrics.push_back({"tracking error mean (m)", base, base - 0.05, base + 0.05});
    m.metrics.push_back({"success rate", m.mode == "single" ? 0.4 : 1.0});
    d.modes.push_back(m);
  }
  const FigureInfo info = RenderComparisonFigure(d, tmp_.path() / "comparison.png");
  const Image img = CheckFile(info, 1600);
  const PanelInfo& tracking = info.Panel("tracking error mean (m)");
  EXPECT_TRUE(ColorNear(PixelAt(img, tracking, Vec2(0.3, 0.1)), ModeColor("partial", 0), 4));
  EXPECT_TRUE(ColorNear(PixelAt(img, tracking, Vec2(1.3, 0.4)), ModeColor("single", 1), 4));
  EXPECT_TRUE(ColorNear(PixelAt(img, tracking, Vec2(0.3, 0.35)), palette::kBackground, 40));
  const PanelInfo& success = info.Panel("success rate");
  EXPECT_TRUE(ColorNear(PixelAt(img, success, Vec2(2.3, 0.9)), ModeColor("consistent", 2), 4));
  EXPECT_EQ(Bytes(info), Bytes(RenderComparisonFigure(d, tmp_.path() / "c2.png")));
  EXPECT_THROW(RenderComparisonFigure(d, BadPath()), core::IoError);
  EXPECT_THROW(RenderComparisonFigure({}, tmp_.path() / "c3.png"), core::IoError);
}

// A metric name wider than its panel wraps onto more lines (instead of running into the next
// panel's title); every plot moves down by the same amount and the bars stay where they belong.
TEST_F(FiguresTest, ComparisonFigureWrapsPanelTitlesWiderThanThePanel) {
  const std::string long_name =
      "pedestrian collisions, robot driving into them (incidents per run), pooled over every seed";
  auto data = [](const std::string& third) {
    ComparisonFigureData d;
    for (const char* mode : {"partial", "consistent"}) {
      ModeMetrics m;
      m.mode = mode;
      for (const std::string& metric : {std::string("a (m)"), std::string("b (m)"), third}) {
        m.metrics.push_back({metric, 0.5});
      }
      d.modes.push_back(m);
    }
    return d;
  };
  const FigureInfo short_titles = RenderComparisonFigure(data("c (m)"), tmp_.path() / "s.png");
  const FigureInfo long_titles = RenderComparisonFigure(data(long_name), tmp_.path() / "l.png");
  const Image img = CheckFile(long_titles, 1600);
  const int extra = long_titles.Panel("a (m)").y - short_titles.Panel("a (m)").y;
  EXPECT_GT(extra, 10);
  EXPECT_EQ(long_titles.height - short_titles.height, extra);
  EXPECT_EQ(long_titles.Panel(long_name).y, long_titles.Panel("a (m)").y);
  const PanelInfo& c = long_titles.Panel(long_name);
  EXPECT_TRUE(ColorNear(PixelAt(img, c, Vec2(1.5, 0.25)), ModeColor("consistent", 1), 4));
}

TEST_F(FiguresTest, WorldFigureShowsGeometryRouteAndPedestrians) {
  WorldFigureData d;
  d.name = "small";
  d.world = testing::SmallWorld();
  d.route = {{3, 4}, {37, 4}, {37, 26}};
  d.pedestrians = {{Vec2(8, 26), 0.3}};
  d.robot = core::Pose2(3, 4, 0);
  d.robot_radius = 0.3;
  const FigureInfo info = RenderWorldFigure(d, tmp_.path() / "world.png", {1000, 2, ""});
  const Image img = CheckFile(info, 1000);
  const PanelInfo& w = info.Panel("world");
  EXPECT_TRUE(ColorNear(PixelAt(img, w, Vec2(27, 20)), palette::kWorldSolid, 6));  // the L
  EXPECT_TRUE(ColorNear(PixelAt(img, w, Vec2(32, 20)), palette::kBackground, 6));  // its notch
  EXPECT_TRUE(ColorNear(PixelAt(img, w, Vec2(20, 4)), palette::kTaughtPath));
  EXPECT_TRUE(ColorNear(PixelAt(img, w, Vec2(8, 26)), palette::kPedestrian));
  EXPECT_THROW(RenderWorldFigure({}, tmp_.path() / "w.png"), core::IoError);
}

TEST_F(FiguresTest, BadOptionsAreConfigErrorsAndWriteNothing) {
  static_assert(std::is_base_of_v<core::Error, RenderError>);
  FigureOptions o;
  o.width = 20000;
  EXPECT_THROW(RenderMapsFigure(SmallMaps(), tmp_.path() / "maps.png", o), core::ConfigError);
  o.width = 1600;
  o.supersample = 5;
  EXPECT_THROW(RenderErrorsFigure({}, tmp_.path() / "errors.png", o), core::ConfigError);
  PlaybackFigureOptions p;
  p.figure.width = 5000;
  p.figure.supersample = 4;
  EXPECT_THROW(RenderPlaybackFigure(SmallPlayback(), tmp_.path() / "p.png", p), core::ConfigError);
  EXPECT_TRUE(std::filesystem::is_empty(tmp_.path()));
}

TEST(FindWidestSpread, FindsTheStationWhereRunsDisagreeMost) {
  const std::vector<core::Pose2> target = testing::Densify({{0, 0}, {50, 0}}, 0.1);
  std::vector<Trajectory> runs;
  for (int r = 0; r < 3; ++r) {
    Trajectory t;
    for (const auto& p : target) {
      const double off = (r - 1) * (0.1 + std::exp(-std::pow((p.x - 31.0) / 3.0, 2)));
      t.poses.emplace_back(p.x, off, 0.0);
    }
    runs.push_back(t);
  }
  const WidestSpread w = FindWidestSpread(target, runs);
  ASSERT_TRUE(w.found);
  EXPECT_NEAR(w.point.x(), 31.0, 0.5);
  EXPECT_NEAR(w.arc_length, 31.0, 0.5);
  EXPECT_NEAR(w.spread, 2.2, 0.05);
  EXPECT_FALSE(FindWidestSpread(target, {runs[0]}).found);
}

}  // namespace
}  // namespace retrace::viz
