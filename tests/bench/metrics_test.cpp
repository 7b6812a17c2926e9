#include "bench/metrics/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "bench/metrics/metrics_json.hpp"
#include "core/rng.hpp"
#include "tests/support/config_key.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
namespace {

using core::Pose2;
using core::Vec2;

constexpr double kTol = 1e-9;
constexpr double kDt = 0.05;  // s, control period of the synthetic runs

// Poses every `step` m along the polyline through `corners`, heading along each leg.
std::vector<Pose2> Polyline(const std::vector<Vec2>& corners, double step) {
  std::vector<Pose2> out;
  for (std::size_t i = 0; i + 1 < corners.size(); ++i) {
    const Vec2 d = corners[i + 1] - corners[i];
    const double heading = std::atan2(d.y(), d.x());
    const int n = static_cast<int>(std::round(d.norm() / step));
    for (int k = 0; k < n; ++k) {
      const Vec2 p = corners[i] + d * (static_cast<double>(k) / n);
      out.emplace_back(p.x(), p.y(), heading);
    }
  }
  const Vec2 d = corners.back() - corners[corners.size() - 2];
  out.emplace_back(corners.back().x(), corners.back().y(), std::atan2(d.y(), d.x()));
  return out;
}

// A teach trace whose single map frame is X_MW * W (a constant drift).
TeachTrace TeachWithMap(const std::vector<Pose2>& X_WR, const Pose2& X_MW = Pose2()) {
  TeachTrace teach;
  teach.X_WR = X_WR;
  teach.X_OR = X_WR;
  TeachMapTrace map;
  for (std::size_t i = 0; i < X_WR.size(); ++i) {
    teach.time.push_back(kDt * static_cast<double>(i));
    map.X_WR.push_back(X_WR[i]);
    map.X_MR.push_back(X_MW * X_WR[i]);
  }
  teach.maps.push_back(map);
  return teach;
}

// A run whose ground truth is X_WR, localized perfectly in map 0 of an identity-drift teach.
RunTrace RunAlong(const std::vector<Pose2>& X_WR, int id = 0) {
  RunTrace run;
  run.run = id;
  run.seed = 100 + static_cast<std::uint64_t>(id);
  run.outcome = Outcome::kSuccess;
  for (std::size_t i = 0; i < X_WR.size(); ++i) {
    PlaybackSample s;
    s.time = kDt * static_cast<double>(i);
    s.X_WR = X_WR[i];
    s.X_MR = X_WR[i];
    s.X_OR = X_WR[i];
    s.clearance = 1.0;
    s.pedestrian_gap = std::numeric_limits<double>::infinity();
    run.samples.push_back(s);
  }
  run.sim_time_s = X_WR.empty() ? 0.0 : run.samples.back().time;
  return run;
}

// The straight taught path along +x, and a run beside it at lateral offset `y` (> 0: left).
std::vector<Pose2> Straight(double length, double y, double step, double x0 = 0.0) {
  return Polyline({{x0, y}, {length, y}}, step);
}

double BruteForceDistance(const std::vector<Pose2>& path, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const Vec2 a = path[i].translation(), d = path[i + 1].translation() - a;
    const double t =
        d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (p - (a + t * d)).norm());
  }
  return best;
}

TEST(Metrics, SummaryHasMeanRmsInterpolatedP95AndMax) {
  const Summary s = Summarize({4.0, 1.0, std::nan(""), 3.0, 2.0});
  EXPECT_EQ(s.count, 4);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.rms, std::sqrt(7.5));
  EXPECT_NEAR(s.p95, 3.85, 1e-12);  // rank 0.95 * 3 = 2.85 between 3 and 4
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  const Summary empty = Summarize({});
  EXPECT_EQ(empty.count, 0);
  EXPECT_TRUE(std::isnan(empty.mean) && std::isnan(empty.rms) && std::isnan(empty.p95) &&
              std::isnan(empty.max));
}

TEST(Metrics, ConstantOffsetRunHasThatTrackingErrorAndSignedLateralOffset) {
  const TeachTrace teach = TeachWithMap(Straight(20.0, 0.0, 0.05));
  const MetricsConfig config;
  for (const double y : {0.1, -0.1}) {
    // A different sample spacing from the teach: distances are to segments, not vertices.
    const RunTrace run = RunAlong(Straight(20.0, y, 0.037));
    const RunMetrics m = ComputeRunMetrics(teach, run, config);
    EXPECT_NEAR(m.tracking_error_m.mean, 0.1, kTol);
    EXPECT_NEAR(m.tracking_error_m.rms, 0.1, kTol);
    EXPECT_NEAR(m.tracking_error_m.p95, 0.1, kTol);
    EXPECT_NEAR(m.tracking_error_m.max, 0.1, kTol);
    EXPECT_EQ(m.tracking_error_m.count, static_cast<int>(run.samples.size()));
    EXPECT_NEAR(m.path_length_m, 20.0, 1e-9);
    EXPECT_NEAR(m.progress_m, 20.0, 1e-9);
    EXPECT_DOUBLE_EQ(m.time_s, run.samples.back().time);
    EXPECT_TRUE(m.success);
    const RunSeries series = ComputeRunSeries(teach, run, config);
    for (const double e : series.lateral_offset_m) EXPECT_NEAR(e, y, kTol);
  }
}

TEST(Metrics, TrackingErrorIsDistanceToSegmentsNotToVertices) {
  const TeachTrace teach = TeachWithMap(Polyline({{0, 0}, {10, 0}, {10, 10}}, 10.0));
  ASSERT_EQ(teach.X_WR.size(), 3u);
  const RunTrace run = RunAlong({Pose2(5, 0.1, 0), Pose2(10.2, 5, 0), Pose2(11, -1, 0)});
  const RunSeries s = ComputeRunSeries(teach, run, MetricsConfig{});
  EXPECT_NEAR(s.tracking_error_m[0], 0.1, kTol);
  EXPECT_NEAR(s.tracking_error_m[1], 0.2, kTol);
  EXPECT_NEAR(s.tracking_error_m[2], std::sqrt(2.0), kTol);
}

TEST(Metrics, TrackingErrorMatchesBruteForceOnALongWindingRoute) {
  // A winding route that crosses itself, 20k samples like the campus route; the run wanders
  // up to 2 m off it and sometimes far away.
  std::vector<Pose2> route;
  for (int i = 0; i < 20000; ++i) {
    const double t = 0.001 * i;
    route.emplace_back(60.0 * std::sin(3.0 * t) + 5.0 * std::cos(17.0 * t),
                       40.0 * std::sin(5.0 * t + 0.3), 0.0);
  }
  const TeachTrace teach = TeachWithMap(route);
  core::Rng rng(7);
  std::vector<Pose2> truth;
  for (int i = 0; i < 20000; i += 40) {
    const double far = (i % 1000 == 0) ? 50.0 : 0.0;
    truth.emplace_back(route[static_cast<std::size_t>(i)].x + rng.Uniform(-2.0, 2.0) + far,
                       route[static_cast<std::size_t>(i)].y + rng.Uniform(-2.0, 2.0), 0.0);
  }
  const RunSeries s = ComputeRunSeries(teach, RunAlong(truth), MetricsConfig{});
  for (std::size_t i = 0; i < truth.size(); ++i) {
    ASSERT_NEAR(s.tracking_error_m[i], BruteForceDistance(route, truth[i].translation()), 1e-9)
        << "sample " << i;
  }
}

TEST(Metrics, RepeatabilityIsTheSampleStdAcrossRunsAndTheSpreadIsMaxMinusMin) {
  const TeachTrace teach = TeachWithMap(Straight(10.0, 0.0, 0.05));
  // The runs start a little behind the start and end beyond the end of the taught path.
  const std::vector<RunTrace> runs = {RunAlong(Straight(10.3, -0.1, 0.043, -0.2), 0),
                                      RunAlong(Straight(10.3, 0.0, 0.05, -0.2), 1),
                                      RunAlong(Straight(10.3, 0.1, 0.061, -0.2), 2)};
  const MetricsConfig config;
  const Repeatability r = ComputeRepeatability(teach, runs, config);
  ASSERT_EQ(r.station_s_m.size(), 21u);  // 0, 0.5, ..., 10
  EXPECT_EQ(r.stations_used, 21);
  EXPECT_NEAR(r.repeatability_m, 0.1, kTol);
  EXPECT_NEAR(r.max_spread_m, 0.2, kTol);
  EXPECT_EQ(r.runs, (std::vector<int>{0, 1, 2}));
  for (std::size_t k = 0; k < r.station_s_m.size(); ++k) {
    EXPECT_NEAR(r.station_s_m[k], 0.5 * static_cast<double>(k), kTol);
    ASSERT_EQ(r.offsets_m[k].size(), 3u);
    EXPECT_NEAR(r.offsets_m[k][0], -0.1, kTol);
    EXPECT_NEAR(r.offsets_m[k][1], 0.0, kTol);
    EXPECT_NEAR(r.offsets_m[k][2], 0.1, kTol);
    EXPECT_NEAR(r.std_m[k], 0.1, kTol);
    EXPECT_NEAR(r.spread_m[k], 0.2, kTol);
  }
  // Aggregate reports the same.
  std::vector<RunMetrics> metrics;
  for (const RunTrace& run : runs) metrics.push_back(ComputeRunMetrics(teach, run, config));
  const AggregateMetrics a = Aggregate(teach, runs, metrics, config);
  EXPECT_NEAR(a.repeatability.repeatability_m, 0.1, kTol);
  EXPECT_NEAR(a.repeatability.max_spread_m, 0.2, kTol);
}

TEST(Metrics, RepeatabilityLeavesStationsARunNeverReachedMissing) {
  const TeachTrace teach = TeachWithMap(Straight(10.0, 0.0, 0.05));
  const std::vector<RunTrace> runs = {RunAlong(Straight(10.0, -0.1, 0.05), 0),
                                      RunAlong(Straight(10.0, 0.1, 0.05), 1),
                                      RunAlong(Straight(5.2, 0.0, 0.05), 2)};
  const Repeatability r = ComputeRepeatability(teach, runs, MetricsConfig{});
  ASSERT_EQ(r.station_s_m.size(), 21u);
  EXPECT_EQ(r.stations_used, 21);
  EXPECT_NEAR(r.offsets_m[10][2], 0.0, kTol);   // s = 5 m: reached
  EXPECT_TRUE(std::isnan(r.offsets_m[11][2]));  // s = 5.5 m: never reached
  EXPECT_NEAR(r.std_m[10], 0.1, kTol);
  EXPECT_NEAR(r.std_m[11], std::sqrt(0.02), kTol);  // two runs at -0.1 and +0.1
  EXPECT_NEAR(r.repeatability_m, (11 * 0.1 + 10 * std::sqrt(0.02)) / 21, kTol);
}

TEST(Metrics, LateralOffsetIsPositiveOnTheLeftInATurn) {
  // Counter-clockwise circle of radius 5: the inside is the left.
  std::vector<Vec2> circle, inside;
  for (int i = 0; i <= 600; ++i) {
    const double a = 1.5 * core::kPi * i / 600.0;
    circle.emplace_back(5.0 * std::sin(a), 5.0 - 5.0 * std::cos(a));
    inside.emplace_back(4.9 * std::sin(a), 5.0 - 4.9 * std::cos(a));
  }
  const TeachTrace teach = TeachWithMap(Polyline(circle, 0.01));
  const Repeatability r =
      ComputeRepeatability(teach, {RunAlong(Polyline(inside, 0.01))}, MetricsConfig{});
  ASSERT_GT(r.station_s_m.size(), 40u);
  for (std::size_t k = 1; k + 1 < r.station_s_m.size(); ++k) {
    EXPECT_NEAR(r.offsets_m[k][0], 0.1, 1e-3) << "station " << k;
  }
}

TEST(Metrics, LocalizationErrorIsZeroAgainstTheLocalTruthOfADriftedMapAndKnownWhenPerturbed) {
  const Pose2 X_MW(3.0, -2.0, 0.7);  // the map frame drifted against the world
  const TeachTrace teach = TeachWithMap(Straight(20.0, 0.0, 0.05), X_MW);
  RunTrace run = RunAlong(Straight(20.0, 0.2, 0.05));
  for (PlaybackSample& s : run.samples) s.X_MR = X_MW * s.X_WR;
  MetricsConfig config;
  RunMetrics m = ComputeRunMetrics(teach, run, config);
  EXPECT_NEAR(m.localization_error_m.max, 0.0, kTol);
  EXPECT_NEAR(m.localization_error_rad.max, 0.0, kTol);
  EXPECT_EQ(m.localization_error_m.count, static_cast<int>(run.samples.size()));
  EXPECT_DOUBLE_EQ(m.lost_fraction, 0.0);

  // 0.3 m ahead and 0.05 rad left in the robot frame; the second half 0.6 m (lost).
  const std::size_t half = run.samples.size() / 2;
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    PlaybackSample& s = run.samples[i];
    s.X_MR = X_MW * s.X_WR * Pose2(i < half ? 0.3 : 0.6, 0.0, 0.05);
  }
  m = ComputeRunMetrics(teach, run, config);
  const double n = static_cast<double>(run.samples.size());
  EXPECT_NEAR(m.localization_error_m.mean, (0.3 * half + 0.6 * (n - half)) / n, 1e-9);
  EXPECT_NEAR(m.localization_error_m.max, 0.6, 1e-9);
  EXPECT_NEAR(m.localization_error_rad.mean, 0.05, 1e-9);
  EXPECT_NEAR(m.localization_error_rad.rms, 0.05, 1e-9);
  EXPECT_NEAR(
      m.lost_fraction,
      static_cast<double>(run.samples.size() - half) / static_cast<double>(run.samples.size()),
      1e-12);
}

TEST(Metrics, LocalizationMatchFollowsTheRightLapWhereThePathRevisitsAPlace) {
  // Lap 1 along y = 0, round a loop, lap 2 along y = 0.3; one map (mode `single`) whose drift
  // grows with the distance driven, so the two laps have different local truths.
  const std::vector<Pose2> X_WR =
      Polyline({{0, 0}, {10, 0}, {10, 5}, {0, 5}, {0, 0.3}, {10, 0.3}}, 0.05);
  TeachTrace teach = TeachWithMap(X_WR);
  std::vector<double> arc(X_WR.size(), 0.0);
  for (std::size_t i = 1; i < X_WR.size(); ++i)
    arc[i] = arc[i - 1] + core::Distance(X_WR[i - 1], X_WR[i]);
  for (std::size_t i = 0; i < X_WR.size(); ++i) {
    const double s = arc[i];
    teach.maps[0].X_MR[i] = Pose2(0.02 * s, -0.01 * s, 0.004 * s) * X_WR[i];
  }
  // The run drives lap 2 at y = 0.1: nearer to lap 1 (0.1 m) than to lap 2 (0.2 m). Its
  // estimate is the local truth of lap 2's sample beside it, i.e. the same teach index.
  RunTrace run = RunAlong(X_WR);
  std::size_t on_lap_2 = 0;
  for (std::size_t i = 0; i < X_WR.size(); ++i) {
    PlaybackSample& s = run.samples[i];
    if (arc[i] > 30.0 && std::abs(X_WR[i].y - 0.3) < 1e-9) {
      s.X_WR = Pose2(X_WR[i].x, 0.1, X_WR[i].theta);
      ++on_lap_2;
    }
    s.X_MR = teach.maps[0].X_MR[i] * X_WR[i].Inverse() * s.X_WR;
  }
  ASSERT_GT(on_lap_2, 150u);
  // Sanity: the first lap's local truth at the same place differs a lot.
  const std::size_t mid_lap_1 = 100, mid_lap_2 = X_WR.size() - 101;  // both at x = 5
  ASSERT_NEAR(X_WR[mid_lap_1].x, X_WR[mid_lap_2].x, 1e-9);
  const Pose2 wrong =
      teach.maps[0].X_MR[mid_lap_1] * X_WR[mid_lap_1].Inverse() * run.samples[mid_lap_2].X_WR;
  ASSERT_GT(core::Distance(wrong, run.samples[mid_lap_2].X_MR), 0.3);

  const RunMetrics m = ComputeRunMetrics(teach, run, MetricsConfig{});
  EXPECT_NEAR(m.localization_error_m.max, 0.0, 1e-9);
  EXPECT_NEAR(m.localization_error_rad.max, 0.0, 1e-9);
}

// Two maps: map 0 is W drifted by X_M0W; map 1 starts at the teach pose at x = 10 (its
// frame is that pose's odometry frame) with a drift of its own.
struct TwoMaps {
  TeachTrace teach;
  Pose2 X_M0W{0.5, -0.3, 0.2};
  Pose2 X_M1W;
};
TwoMaps MakeTwoMaps() {
  TwoMaps t;
  const std::vector<Pose2> X_WR = Straight(20.0, 0.0, 0.05);
  t.teach = TeachWithMap(X_WR, t.X_M0W);
  t.X_M1W = Pose2(0.1, 0.2, -0.15) * Pose2(10.0, 0.0, 0.0).Inverse();
  TeachMapTrace map0, map1;
  for (const Pose2& X : X_WR) {
    if (X.x <= 10.0 + 1e-9) {
      map0.X_WR.push_back(X);
      map0.X_MR.push_back(t.X_M0W * X);
    }
    if (X.x >= 10.0 - 1e-9) {
      map1.X_WR.push_back(X);
      map1.X_MR.push_back(t.X_M1W * X);
    }
  }
  t.teach.maps = {map0, map1};
  return t;
}

TEST(Metrics, SwitchErrorIsTheLocalizationErrorInTheNewMapRightAfterTheSwitch) {
  const TwoMaps t = MakeTwoMaps();
  const MetricsConfig config;
  std::vector<RunTrace> runs;
  std::vector<RunMetrics> metrics;
  for (const double error : {0.1, 0.3}) {
    RunTrace run = RunAlong(Straight(20.0, 0.05, 0.05), static_cast<int>(runs.size()));
    for (PlaybackSample& s : run.samples) {
      s.map_index = s.X_WR.x < 10.0 ? 0 : 1;
      s.X_MR = (s.map_index == 0 ? t.X_M0W : t.X_M1W) * s.X_WR;
    }
    SwitchRecord sw;
    sw.time = 10.0;
    sw.from = 0;
    sw.to = 1;
    sw.X_WR = Pose2(10.02, 0.05, 0.01);
    sw.X_MnR = t.X_M1W * sw.X_WR * Pose2(0.0, error, -error);
    run.switches.push_back(sw);
    runs.push_back(run);
    metrics.push_back(ComputeRunMetrics(t.teach, run, config));
    const RunMetrics& m = metrics.back();
    EXPECT_NEAR(m.localization_error_m.max, 0.0, 1e-9);  // the samples are exact in both maps
    ASSERT_EQ(m.switches.size(), 1u);
    EXPECT_EQ(m.switches[0].from, 0);
    EXPECT_EQ(m.switches[0].to, 1);
    EXPECT_NEAR(m.switches[0].error_m, error, 1e-9);
    EXPECT_NEAR(m.switches[0].error_rad, error, 1e-9);
    EXPECT_NEAR(m.switch_error_max_m, error, 1e-9);
  }
  const AggregateMetrics a = Aggregate(t.teach, runs, metrics, config);
  EXPECT_EQ(a.switch_error.count, 2);
  EXPECT_NEAR(a.switch_error.mean_m, 0.2, 1e-9);
  EXPECT_NEAR(a.switch_error.max_m, 0.3, 1e-9);
  EXPECT_NEAR(a.switch_error.mean_rad, 0.2, 1e-9);
  EXPECT_NEAR(a.switch_error.max_rad, 0.3, 1e-9);

  // A switch to a map the teach does not have has no error, and does not count.
  RunTrace bad = runs[0];
  bad.switches[0].to = 5;
  const RunMetrics mb = ComputeRunMetrics(t.teach, bad, config);
  ASSERT_EQ(mb.switches.size(), 1u);
  EXPECT_TRUE(std::isnan(mb.switches[0].error_m));
  EXPECT_TRUE(std::isnan(mb.switch_error_max_m));
}

TEST(Metrics, ContactsOfTheSameKindCloseInTimeAreOneIncident) {
  const TeachTrace teach = TeachWithMap(Straight(10.0, 0.0, 0.05));
  RunTrace run = RunAlong(Straight(10.0, 0.0, 0.05));
  auto contact = [&](double time, sim::CollisionKind kind, int id = -1) {
    sim::CollisionEvent e;
    e.time = time;
    e.kind = kind;
    e.pedestrian_id = id;
    run.collisions.push_back(e);
  };
  using sim::CollisionKind;
  contact(10.0, CollisionKind::kStatic);
  contact(10.2, CollisionKind::kStatic);
  contact(10.45, CollisionKind::kStatic);
  contact(3.0, CollisionKind::kPedestrian, 1);
  contact(3.1, CollisionKind::kPedestrian, 2);  // another pedestrian: another incident
  contact(3.5, CollisionKind::kPedestrian, 1);
  const MetricsConfig config;
  RunMetrics m = ComputeRunMetrics(teach, run, config);
  EXPECT_EQ(m.collisions.static_incidents, 1);
  EXPECT_EQ(m.collisions.static_events, 3);
  EXPECT_EQ(m.collisions.pedestrian_incidents, 2);
  EXPECT_EQ(m.collisions.pedestrian_events, 3);

  contact(15.45, CollisionKind::kStatic);  // 5 s later
  m = ComputeRunMetrics(teach, run, config);
  EXPECT_EQ(m.collisions.static_incidents, 2);
  EXPECT_EQ(m.collisions.static_events, 4);

  // Minimum clearance and pedestrian gap over the samples.
  run.samples[7].clearance = 0.12;
  run.samples[9].pedestrian_gap = 0.4;
  run.samples[11].pedestrian_gap = 0.9;
  m = ComputeRunMetrics(teach, run, config);
  EXPECT_DOUBLE_EQ(m.collisions.min_clearance_m, 0.12);
  EXPECT_DOUBLE_EQ(m.collisions.min_pedestrian_gap_m, 0.4);
  // Aggregate: totals, and runs with a collision.
  const RunTrace clean = RunAlong(Straight(10.0, 0.0, 0.05), 1);
  const AggregateMetrics a =
      Aggregate(teach, {run, clean}, {m, ComputeRunMetrics(teach, clean, config)}, config);
  EXPECT_EQ(a.collisions.static_incidents, 2);
  EXPECT_EQ(a.collisions.pedestrian_incidents, 2);
  EXPECT_EQ(a.runs_with_collision, 1);
  EXPECT_DOUBLE_EQ(a.collisions.min_clearance_m, 0.12);
}

// Who ran into whom: a pedestrian incident is the robot's when it drove towards the contact
// point; walking into a standing robot, or into its side or back, is the pedestrian's.
TEST(Metrics, APedestrianIncidentIsTheRobotsOnlyWhenItDroveTowardsTheContact) {
  const TeachTrace teach = TeachWithMap(Straight(10.0, 0.0, 0.05));
  RunTrace run = RunAlong(Straight(10.0, 0.0, 0.05));  // +x at 1 m/s for 10 s
  for (int i = 1; i <= 40; ++i) {                      // then 2 s standing still
    PlaybackSample s = run.samples.back();
    s.time += kDt;
    run.samples.push_back(s);
  }
  int id = 0;
  auto contact = [&](double time, double x, double y) {
    sim::CollisionEvent e;
    e.time = time;
    e.kind = sim::CollisionKind::kPedestrian;
    e.pedestrian_id = id++;
    e.point_W = {x, y};
    run.collisions.push_back(e);
  };
  contact(3.0, 3.3, 0.05);   // ahead while driving: the robot's
  contact(5.0, 4.7, 0.0);    // from behind
  contact(7.0, 7.0, 0.3);    // from the side
  contact(11.0, 10.3, 0.0);  // ahead, but the robot stands
  contact(0.0, 0.3, 0.0);    // at the first sample: no speed known
  const MetricsConfig config;
  const RunMetrics m = ComputeRunMetrics(teach, run, config);
  EXPECT_EQ(m.collisions.pedestrian_incidents, 5);
  EXPECT_EQ(m.collisions.pedestrian_incidents_robot_driving, 1);
  const AggregateMetrics a = Aggregate(teach, {run, run}, {m, m}, config);
  EXPECT_EQ(a.collisions.pedestrian_incidents_robot_driving, 2);

  // Slower than collision_driving_speed towards the contact: not the robot's.
  MetricsConfig strict = config;
  strict.collision_driving_speed = 1.5;
  EXPECT_EQ(ComputeRunMetrics(teach, run, strict).collisions.pedestrian_incidents_robot_driving, 0);
}

TEST(Metrics, DynamicPointRatiosAreNaNWhenUndefined) {
  const TeachTrace teach = TeachWithMap(Straight(10.0, 0.0, 0.05));
  RunTrace run = RunAlong(Straight(10.0, 0.0, 0.05));
  const MetricsConfig config;
  RunMetrics m = ComputeRunMetrics(teach, run, config);  // no updates at all
  EXPECT_TRUE(std::isnan(m.dynamic_points.rejected_fraction));
  EXPECT_TRUE(std::isnan(m.dynamic_points.precision));
  EXPECT_TRUE(std::isnan(m.dynamic_points.recall));
  EXPECT_TRUE(std::isnan(m.cpu.localizer_update_mean_ms));

  LocalizerSample u;
  u.beams_tested = 100;  // nothing rejected, nothing hit a pedestrian
  u.cpu_s = 0.002;
  run.updates.push_back(u);
  m = ComputeRunMetrics(teach, run, config);
  EXPECT_DOUBLE_EQ(m.dynamic_points.rejected_fraction, 0.0);
  EXPECT_TRUE(std::isnan(m.dynamic_points.precision));
  EXPECT_TRUE(std::isnan(m.dynamic_points.recall));
  EXPECT_TRUE(ToJson(m)["dynamic_points"]["precision"].is_null());

  u = {};
  u.beams_tested = 50;
  u.beams_rejected = 15;
  u.true_positive = 9;
  u.false_positive = 6;
  u.false_negative = 3;
  u.cpu_s = 0.004;
  run.updates.push_back(u);
  run.sim_time_s = 10.0;
  run.cpu_time_s = 2.0;
  m = ComputeRunMetrics(teach, run, config);
  EXPECT_EQ(m.dynamic_points.beams_tested, 150);
  EXPECT_DOUBLE_EQ(m.dynamic_points.rejected_fraction, 0.1);
  EXPECT_DOUBLE_EQ(m.dynamic_points.precision, 0.6);
  EXPECT_DOUBLE_EQ(m.dynamic_points.recall, 0.75);
  EXPECT_EQ(m.cpu.localizer_updates, 2);
  EXPECT_NEAR(m.cpu.localizer_update_mean_ms, 3.0, 1e-12);
  EXPECT_NEAR(m.cpu.localizer_update_max_ms, 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.cpu.real_time_factor, 5.0);

  // Recall 0 (a pedestrian missed), precision undefined (nothing rejected).
  RunTrace missed = RunAlong(Straight(10.0, 0.0, 0.05), 1);
  u = {};
  u.beams_tested = 10;
  u.false_negative = 2;
  missed.updates.push_back(u);
  const RunMetrics mm = ComputeRunMetrics(teach, missed, config);
  EXPECT_DOUBLE_EQ(mm.dynamic_points.recall, 0.0);
  EXPECT_TRUE(std::isnan(mm.dynamic_points.precision));
  EXPECT_TRUE(std::isnan(mm.cpu.real_time_factor));  // no CPU time recorded

  // Aggregate: ratios of the totals.
  const AggregateMetrics a = Aggregate(teach, {run, missed}, {m, mm}, config);
  EXPECT_EQ(a.dynamic_points.beams_tested, 160);
  EXPECT_DOUBLE_EQ(a.dynamic_points.precision, 0.6);
  EXPECT_DOUBLE_EQ(a.dynamic_points.recall, 9.0 / 14.0);
  EXPECT_EQ(a.cpu.localizer_updates, 3);
  EXPECT_NEAR(a.cpu.localizer_update_mean_ms, 2.0, 1e-12);  // (2 + 4 + 0) / 3
  EXPECT_DOUBLE_EQ(a.cpu.real_time_factor, (10.0 + missed.sim_time_s) / 2.0);
}

TEST(Metrics, AggregatePoolsAllSamplesAndAveragesPerRunValues) {
  const TeachTrace teach = TeachWithMap(Straight(10.0, 0.0, 0.05));
  RunTrace near = RunAlong(Straight(10.0, 0.1, 0.05), 0);  // 201 samples at 0.1 m
  RunTrace far = RunAlong(Straight(10.0, 0.3, 0.025), 1);  // 401 samples at 0.3 m
  far.outcome = Outcome::kLost;
  const MetricsConfig config;
  const std::vector<RunTrace> runs = {near, far};
  const std::vector<RunMetrics> metrics = {ComputeRunMetrics(teach, near, config),
                                           ComputeRunMetrics(teach, far, config)};
  const AggregateMetrics a = Aggregate(teach, runs, metrics, config);
  EXPECT_EQ(a.runs, 2);
  EXPECT_EQ(a.successes, 1);
  EXPECT_DOUBLE_EQ(a.success_rate, 0.5);
  EXPECT_EQ(a.outcome_counts[static_cast<int>(Outcome::kSuccess)], 1);
  EXPECT_EQ(a.outcome_counts[static_cast<int>(Outcome::kLost)], 1);
  EXPECT_EQ(a.outcome_counts[static_cast<int>(Outcome::kTimeout)], 0);
  const double n_near = 201, n_far = 401;
  EXPECT_EQ(a.tracking_error_m_pooled.count, 602);
  EXPECT_NEAR(a.tracking_error_m_pooled.mean, (0.1 * n_near + 0.3 * n_far) / (n_near + n_far),
              1e-9);
  EXPECT_NEAR(a.tracking_error_m_pooled.rms,
              std::sqrt((0.01 * n_near + 0.09 * n_far) / (n_near + n_far)), 1e-9);
  EXPECT_NEAR(a.tracking_error_m_pooled.max, 0.3, 1e-9);
  EXPECT_EQ(a.tracking_error_m_run_mean.count, 2);
  EXPECT_NEAR(a.tracking_error_m_run_mean.mean, 0.2, 1e-9);
  EXPECT_NEAR(a.tracking_error_m_run_mean.max, 0.2, 1e-9);
  EXPECT_NEAR(a.taught_path_length_m, 10.0, 1e-9);
  EXPECT_NEAR(a.mean_path_length_m, 10.0, 1e-9);
  EXPECT_NEAR(a.mean_time_s, (10.0 + 20.0) / 2.0, 1e-9);
  EXPECT_DOUBLE_EQ(a.localization_error_m_pooled.max, 0.0);
  EXPECT_DOUBLE_EQ(a.lost_fraction_pooled, 0.0);
}

void ExpectKeys(const nlohmann::json& j, const std::vector<std::string>& keys) {
  ASSERT_TRUE(j.is_object());
  for (const std::string& k : keys) EXPECT_TRUE(j.contains(k)) << "missing key " << k;
  EXPECT_EQ(j.size(), keys.size()) << j.dump();
}

// Two runs along a 10 m straight taught path: run 3 all the way 0.1 m to the left, with a switch
// to a map that does not exist (a NaN error); run 4 stops at 6 m, 0.1 m to the right.
struct TwoRuns {
  TeachTrace teach = TeachWithMap(Straight(10.0, 0.0, 0.05));
  std::vector<RunTrace> runs = {RunAlong(Straight(10.0, 0.1, 0.05), 3),
                                RunAlong(Straight(6.0, -0.1, 0.05), 4)};
  MetricsConfig config;
  std::vector<RunMetrics> metrics;

  TwoRuns() {
    SwitchRecord sw;
    sw.to = 1;  // no such map: NaN error
    runs[0].switches.push_back(sw);
    for (const RunTrace& run : runs) metrics.push_back(ComputeRunMetrics(teach, run, config));
  }
  AggregateMetrics Aggregated() const { return Aggregate(teach, runs, metrics, config); }
};

TEST(Metrics, RunJsonHasTheDocumentedKeysAndNullForNaN) {
  const TwoRuns two;
  const nlohmann::json r = ToJson(two.metrics[0]);
  ExpectKeys(r, {"run", "seed", "outcome", "success", "samples", "time_s", "path_length_m",
                 "progress_m", "tracking_error_m", "localization_error_m", "localization_error_rad",
                 "lost_fraction", "localizer", "collisions", "switch_error", "dynamic_points",
                 "social", "cpu"});
  ExpectKeys(r["tracking_error_m"], {"mean", "rms", "p95", "max", "count"});
  ExpectKeys(r["collisions"],
             {"static_incidents", "pedestrian_incidents", "pedestrian_incidents_robot_driving",
              "static_events", "pedestrian_events", "min_clearance_m", "min_pedestrian_gap_m"});
  ExpectKeys(r["switch_error"], {"count", "max_m", "max_rad", "switches"});
  ExpectKeys(r["switch_error"]["switches"][0], {"time_s", "from", "to", "error_m", "error_rad"});
  ExpectKeys(r["dynamic_points"],
             {"beams_tested", "beams_rejected", "true_positive", "false_positive", "false_negative",
              "rejected_fraction", "precision", "recall"});
  ExpectKeys(r["cpu"], {"localizer_updates", "localizer_update_mean_ms", "localizer_update_max_ms",
                        "sim_time_s", "cpu_time_s", "real_time_factor"});
  EXPECT_EQ(r["outcome"], "success");
  EXPECT_EQ(r["run"], 3);
  EXPECT_EQ(r["seed"], 103u);
  EXPECT_NEAR(r["tracking_error_m"]["rms"].get<double>(), 0.1, kTol);
  EXPECT_TRUE(r["switch_error"]["switches"][0]["error_m"].is_null());
  EXPECT_TRUE(r["switch_error"]["max_m"].is_null());
  EXPECT_TRUE(r["collisions"]["min_pedestrian_gap_m"].is_null());  // inf: none seen
  EXPECT_TRUE(r["dynamic_points"]["precision"].is_null());
  EXPECT_TRUE(r["cpu"]["real_time_factor"].is_null());
}

TEST(Metrics, AggregateJsonHasTheDocumentedKeys) {
  const TwoRuns two;
  const nlohmann::json a = ToJson(two.Aggregated());
  ExpectKeys(a, {"runs",
                 "successes",
                 "success_rate",
                 "outcomes",
                 "taught_path_length_m",
                 "mean_time_s",
                 "mean_path_length_m",
                 "mean_progress_m",
                 "tracking_error_m",
                 "localization_error_m",
                 "localization_error_rad",
                 "lost_fraction",
                 "localizer",
                 "repeatability_m",
                 "repeatability_max_spread_m",
                 "repeatability_stations_used",
                 "collisions",
                 "switch_error",
                 "dynamic_points",
                 "maps",
                 "map_quality",
                 "switching",
                 "scan_matching",
                 "social",
                 "cpu"});
  ExpectKeys(a["social"], {"intimate_time_s", "personal_time_s", "min_ttc_s", "path_efficiency",
                           "time_efficiency", "jerk_m_s3", "crowd"});
  ExpectKeys(a["social"]["crowd"], {"encounters", "passed", "yielded", "blocked", "standing",
                                    "wait_time_s", "max_wait_s"});
  ExpectKeys(a["switching"], {"minimum_maps", "revisiting_maps", "switch_travel_m", "reasons",
                              "switches_by_reason"});
  ExpectKeys(a["outcomes"], {"success", "timeout", "collision", "lost"});
  ExpectKeys(a["map_quality"], {"distortion_m", "agreement", "per_map"});
  ExpectKeys(a["map_quality"]["distortion_m"], {"rms", "max"});
  ExpectKeys(a["scan_matching"], {"matched", "empty_map", "few_points", "degenerate", "poor_fit",
                                  "keyframes", "refused"});
  ExpectKeys(a["tracking_error_m"], {"pooled", "run_mean"});
  ExpectKeys(a["tracking_error_m"]["pooled"], {"mean", "rms", "p95", "max", "count"});
  ExpectKeys(a["lost_fraction"], {"pooled", "run_mean"});
  ExpectKeys(a["localizer"],
             {"lost_time_s", "lost_spells", "reacquisitions", "max_jump_m", "max_jump_time_s",
              "max_error_increase_m", "max_error_increase_time_s", "reacquisitions_closer",
              "reacquisitions_wrong", "off_map_time_s", "silent_failure_time_s",
              "longest_silent_failure_s", "false_alarm_time_s", "wrong_switches"});
  ExpectKeys(a["switch_error"], {"count", "mean_m", "max_m", "mean_rad", "max_rad"});
  ExpectKeys(a["collisions"],
             {"static_incidents", "pedestrian_incidents", "pedestrian_incidents_robot_driving",
              "static_events", "pedestrian_events", "min_clearance_m", "min_pedestrian_gap_m",
              "runs_with_collision"});
  EXPECT_EQ(a["outcomes"]["success"], 2);
  EXPECT_TRUE(a["switch_error"]["mean_m"].is_null());
  EXPECT_EQ(a["switch_error"]["count"], 0);
  EXPECT_NO_THROW((void)a.dump());
}

TEST(Metrics, RepeatabilityGoesToTheJsonAndItsStationsToACsv) {
  const TwoRuns two;
  const AggregateMetrics aggregate = two.Aggregated();
  const nlohmann::json a = ToJson(aggregate);
  // The stations themselves go to a CSV: s, run 3, run 4, std, spread.
  const retrace::testing::TempDir tmp;
  WriteRepeatabilityCsv(tmp.path() / "repeatability.csv", aggregate.repeatability);
  std::ifstream in(tmp.path() / "repeatability.csv");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 22u);  // header + 21 stations
  EXPECT_EQ(lines[0], "s_m,offset_run3_m,offset_run4_m,std_m,spread_m");
  EXPECT_EQ(lines[3].substr(0, 11), "1,0.1,-0.1,");
  EXPECT_EQ(lines[21], "10,0.1,nan,nan,nan");  // run 4 stopped at 6 m
  EXPECT_NEAR(a["repeatability_m"].get<double>(), std::sqrt(0.02), 1e-9);
  EXPECT_EQ(a["repeatability_stations_used"], 13);  // 0 .. 6 m
}

TEST(Metrics, EmptyRunsAndAnEmptyTeachDoNotCrash) {
  const MetricsConfig config;
  const TeachTrace teach = TeachWithMap(Straight(10.0, 0.0, 0.05));
  const RunTrace empty;
  const RunMetrics m = ComputeRunMetrics(teach, empty, config);
  EXPECT_EQ(m.samples, 0);
  EXPECT_EQ(m.tracking_error_m.count, 0);
  EXPECT_TRUE(std::isnan(m.tracking_error_m.rms));
  EXPECT_TRUE(std::isnan(m.lost_fraction));
  EXPECT_TRUE(std::isnan(m.collisions.min_clearance_m));
  EXPECT_DOUBLE_EQ(m.time_s, 0.0);
  EXPECT_NO_THROW((void)ToJson(m).dump());

  const AggregateMetrics a = Aggregate(teach, {empty, empty}, {m, m}, config);
  EXPECT_EQ(a.runs, 2);
  EXPECT_EQ(a.tracking_error_m_pooled.count, 0);
  EXPECT_EQ(a.repeatability.stations_used, 0);
  EXPECT_TRUE(std::isnan(a.repeatability.repeatability_m));
  EXPECT_NO_THROW((void)ToJson(a).dump());

  const AggregateMetrics none = Aggregate(teach, {}, {}, config);
  EXPECT_EQ(none.runs, 0);
  EXPECT_TRUE(std::isnan(none.success_rate));
  EXPECT_TRUE(ToJson(none)["success_rate"].is_null());

  // No teach at all, and a run whose map index has no teach map.
  RunTrace run = RunAlong(Straight(5.0, 0.0, 0.05));
  for (PlaybackSample& s : run.samples) s.map_index = 3;
  const RunMetrics no_teach = ComputeRunMetrics(TeachTrace{}, run, config);
  EXPECT_EQ(no_teach.tracking_error_m.count, 0);
  EXPECT_EQ(no_teach.localization_error_m.count, 0);
  EXPECT_NEAR(no_teach.path_length_m, 5.0, 1e-9);
  const RunMetrics no_map = ComputeRunMetrics(teach, run, config);
  EXPECT_EQ(no_map.tracking_error_m.count, static_cast<int>(run.samples.size()));
  EXPECT_EQ(no_map.localization_error_m.count, 0);
  EXPECT_NO_THROW((void)ToJson(Aggregate(TeachTrace{}, {run}, {no_teach}, config)).dump());
  // A one-sample teach.
  const TeachTrace point = TeachWithMap({Pose2(1, 1, 0)});
  const RunMetrics at_point = ComputeRunMetrics(point, run, config);
  EXPECT_NEAR(at_point.tracking_error_m.max, std::hypot(4.0, 1.0), 1e-9);
}

TEST(MetricsConfig, ValidateNamesTheOffendingKey) {
  using testing::ValidationErrorKey;
  EXPECT_EQ(ValidationErrorKey(MetricsConfig{}), testing::kValid);
  EXPECT_EQ(ValidationErrorKey<MetricsConfig>([](auto& c) { c.station_spacing = 0.0; }),
            "station_spacing");
  EXPECT_EQ(ValidationErrorKey<MetricsConfig>([](auto& c) { c.lost_error = -1.0; }), "lost_error");
  EXPECT_EQ(ValidationErrorKey<MetricsConfig>([](auto& c) { c.collision_merge_time = -0.1; }),
            "collision_merge_time");
  EXPECT_EQ(ValidationErrorKey<MetricsConfig>([](auto& c) { c.collision_merge_time = 0.0; }),
            testing::kValid);
  EXPECT_EQ(ValidationErrorKey<MetricsConfig>([](auto& c) { c.match_window = 0.0; }),
            "match_window");
  EXPECT_EQ(
      ValidationErrorKey<MetricsConfig>([](auto& c) { c.match_fallback_distance = std::nan(""); }),
      "match_fallback_distance");
}

}  // namespace
}  // namespace retrace::bench
