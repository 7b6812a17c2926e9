// What the map does not hold (bench/calibration/unmapped_calibration.hpp): the walk's lengths
// through unknown and band cells, the Poisson rates recovered from beams drawn with known ones,
// and the static test that tells a chair from a passer-by.
#include "bench/calibration/unmapped_calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "bench/engine/clutter.hpp"
#include "core/rng.hpp"
#include "io/ros_map.hpp"

namespace retrace::bench::unmapped_calibration_test {

constexpr double kInf = std::numeric_limits<double>::infinity();

// 20 m × 10 m at 0.1 m: known free for x < 12 m, unknown beyond; the route along y = 5 m.
core::OccupancyGrid HalfKnown() {
  core::OccupancyGrid grid(200, 100, 0.1, core::Vec2(0.0, 0.0));
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 120; ++x) grid.SetProbability({x, y}, io::kRosMapFreeProbability);
  return grid;
}

const std::vector<core::Vec2> kRoute = {{0.5, 5.0}, {11.5, 5.0}};

TEST(UnmappedCalibration, WalkMeasuresTheRayInUnknownAndBandCells) {
  const core::OccupancyGrid grid = HalfKnown();
  ClutterConfig clutter;  // band 3 m, clearance 0.3 m: with radius 0.3 the corridor is 0.6 m
  const UnmappedMap map(grid, 0.65, kRoute, clutter, 0.3);
  BandObservations obs = map.NewObservations();
  // Along the route into the unknown half up to the map's range of 16 m: 12 − 2 m known (in
  // the corridor), then 6 m unknown.
  const UnmappedBeam along = map.Walk(0.0, {2.0, 5.05}, {1.0, 0.0}, kInf, 16.0, &obs);
  EXPECT_NEAR(along.unknown_m, 6.0, 1e-4);
  EXPECT_NEAR(along.band_m, 0.0, 1e-6);
  // Across the band, up from the route: the band is 0.6 to 3 m off it, less clutter.gap (0.1 m)
  // of known free cells at the grid's edge (y = 10 m is 5 m away: no effect).
  const UnmappedBeam up = map.Walk(1.0, {6.05, 5.0}, {0.0, 1.0}, 4.0, 4.5, &obs);
  EXPECT_NEAR(up.band_m, 3.0 - 0.6, 0.1 + 1e-6);
  EXPECT_EQ(up.end, BeamEnd::kOther);  // ends beyond the band, 4 m off the route
  const UnmappedBeam hit = map.Walk(2.0, {6.05, 5.0}, {0.0, 1.0}, 2.0, 4.5, &obs);
  EXPECT_EQ(hit.end, BeamEnd::kBand);
  const UnmappedBeam in_unknown = map.Walk(3.0, {2.0, 5.05}, {1.0, 0.0}, 13.0, 16.0, &obs);
  EXPECT_EQ(in_unknown.end, BeamEnd::kUnknown);  // at x = 15 m
  EXPECT_NEAR(in_unknown.unknown_m, 3.0, 1e-4);
}

TEST(UnmappedCalibration, RatesOfDrawnBeamsAreRecovered) {
  // Rays that cross 5 m of unknown cells behind 3 m of band, each hit at exponential depths:
  // free path 1.3 m in the unknown cells, 0.4 hits per m in the band.
  constexpr double kFreePath = 1.3, kBandRate = 0.4, kWidth = 0.8;
  core::Rng rng(7);
  std::vector<UnmappedBeam> beams;
  for (int i = 0; i < 20000; ++i) {
    UnmappedBeam b{static_cast<double>(i), kInf, 8.0};
    const double in_band = -std::log(1.0 - rng.Uniform()) / kBandRate;
    const double in_unknown = -kFreePath * std::log(1.0 - rng.Uniform());
    if (in_band < 3.0) {
      b.reading = in_band;
      b.band_m = static_cast<float>(in_band);
      b.end = BeamEnd::kBand;
      b.end_static = true;
    } else if (in_unknown < 5.0) {
      b.reading = 3.0 + in_unknown;
      b.band_m = 3.0F;
      b.unknown_m = static_cast<float>(in_unknown);
      b.end = BeamEnd::kUnknown;
    } else {
      b.reading = i % 2 ? 8.0 : kInf;  // the map's wall, or no return: passed everything
      b.band_m = 3.0F;
      b.unknown_m = 5.0F;
    }
    beams.push_back(b);
  }
  // Plus readings beyond the wall: left out, they change nothing.
  for (int i = 0; i < 3000; ++i) beams.push_back({0.0, 20.0, 8.0, 5.0F, 3.0F});
  const UnmappedFit fit = FitUnmapped(beams, 0.2, 0.2, kWidth);
  EXPECT_EQ(fit.unexplained, 3000U);
  EXPECT_NEAR(fit.unknown_free_path, kFreePath, 0.04 * kFreePath);
  EXPECT_NEAR(fit.density * kWidth, kBandRate, 0.04 * kBandRate);
}

TEST(UnmappedCalibration, HitsThatStayAreStaticPassersByAreNot) {
  const core::OccupancyGrid grid = HalfKnown();
  const UnmappedMap map(grid, 0.65, kRoute, ClutterConfig{}, 0.3);
  BandObservations obs = map.NewObservations();
  std::vector<UnmappedBeam> beams;
  // A chair 2 m up from the route at x = 4 m: every ray up there ends on it.
  for (int i = 0; i < 5; ++i) beams.push_back(map.Walk(i, {4.05, 5.0}, {0.0, 1.0}, 2.0, 4.5, &obs));
  // A passer-by 2 m up at x = 8 m, seen once; the other rays there go through to 4 m.
  beams.push_back(map.Walk(10.0, {8.05, 5.0}, {0.0, 1.0}, 2.0, 4.5, &obs));
  for (int i = 0; i < 5; ++i)
    beams.push_back(map.Walk(11 + i, {8.05, 5.0}, {0.0, 1.0}, 4.0, 4.5, &obs));
  map.MarkStaticHits(obs, beams);
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(beams[i].end_static) << i;
  EXPECT_EQ(beams[5].end, BeamEnd::kBand);
  EXPECT_FALSE(beams[5].end_static);
}

TEST(UnmappedCalibration, MeanWidthIsThePerimeterOverPi) {
  ClutterConfig chairs;
  chairs.kinds = {ClutterKind::kChair};
  EXPECT_NEAR(MeanClutterWidth(chairs), 2.0 / std::numbers::pi, 1e-12);  // 0.5 m square
  ClutterConfig bins;
  bins.kinds = {ClutterKind::kBin};
  EXPECT_NEAR(MeanClutterWidth(bins), 0.4, 1e-12);
}

}  // namespace retrace::bench::unmapped_calibration_test
