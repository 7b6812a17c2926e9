#pragma once
// What a log's map does not hold, measured on its real scans (docs/METHOD.md, "What the map does
// not hold"): how far rays travel through the map's unknown cells before they meet something
// (a world file's `unknown_free_path`), and how many unmapped objects stand in the mapped free
// space beside the route (the `clutter.density` of chairs, bins, bikes and boxes). Both are
// maximum-likelihood rates of a Poisson process along the rays: hits divided by exposure.
//
// Each beam is walked through the map from the LiDAR to where it ends (its reading, or the
// first occupied cell when it reads farther or nothing), adding up its length in unknown cells
// and in the clutter's band (known free cells within clutter.band of the route, outside the
// corridor of robot radius + clutter.clearance, clutter.gap clear of every cell that is not
// known free: readings that end nearer a wall are mostly the map's walls a cell off). A reading
// short of the map's range by more than the margin is a hit where it ends (beams without a return
// or reading beyond the map's range are left out: the sensor's random readings and dropouts): in an
// unknown cell it counts for the free path, in a band cell for the clutter when it stays (hit again
// by later rays, not passed through: the window's own occupancy of that cell; MarkStaticHits). An
// object of the clutter's kinds at a uniform yaw blocks a ray that passes within its mean width
// (Cauchy: perimeter / π) of its centre, so the density is the band's hits over the band's exposure
// times that width.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "bench/engine/clutter.hpp"
#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "io/tum.hpp"

namespace retrace::bench {

/// Where a short reading ends.
enum class BeamEnd : std::uint8_t { kBand, kUnknown, kOther };

/// One beam walked through the map.
struct UnmappedBeam {
  double t = 0.0;          ///< log time of its scan (s, as --from/--to)
  double reading = 0.0;    ///< m; +inf for no return
  double map_range = 0.0;  ///< m: first occupied cell (unknown cells open), range_max if none
  float unknown_m = 0.0F;  ///< m of the ray in unknown cells, up to where it ends
  float band_m = 0.0F;     ///< m of the ray in the band's known free cells, up to where it ends
  BeamEnd end = BeamEnd::kOther;  ///< the cell of the reading's end, when short of map_range
  /// The band cell the reading ends in (end == kBand), and whether what it hit stays there
  /// (MarkStaticHits).
  std::uint32_t end_cell = 0;
  bool end_static = false;
};

/// How often the window's rays ended in each band cell and how often they went through it: an
/// occupancy grid of the window's own readings over the band.
struct BandObservations {
  std::vector<std::uint32_t> hits, passes;  ///< per map cell
};

/// The map's cells sorted out for the walk: unknown, and known free within the band.
class UnmappedMap {
 public:
  /// `route` (the map's frame M) is the driven path; the band and corridor are the clutter's.
  UnmappedMap(const core::OccupancyGrid& grid, double occupied_threshold,
              std::span<const core::Vec2> route, const ClutterConfig& clutter, double robot_radius);

  /// The beam from `origin` along the unit `dir` that read `reading` (m, +inf for none), with
  /// the map's range `map_range` (m).
  UnmappedBeam Walk(double t, const core::Vec2& origin, const core::Vec2& dir, double reading,
                    double map_range, BandObservations* observations) const;

  /// Marks the beams whose reading ends short in the band on something that stays: a cell
  /// within one cell of the end that was hit at least twice and at least as often as rays went
  /// through it. People walk on and leave their cells mostly passed through; a chair does not.
  void MarkStaticHits(const BandObservations& observations, std::span<UnmappedBeam> beams) const;

  BandObservations NewObservations() const;

 private:
  enum Kind : std::uint8_t { kOpen = 0, kUnknownCell = 1, kBandCell = 2 };
  Kind KindAt(core::CellIndex c) const;

  core::OccupancyGrid grid_;
  std::vector<std::uint8_t> kinds_;  // per cell: Kind, occupied cells kOpen
};

/// The rates fitted to a set of beams.
struct UnmappedFit {
  std::size_t beams = 0;           ///< beams with a reading
  std::size_t unexplained = 0;     ///< of those: beyond the map's range (left out)
  std::size_t short_readings = 0;  ///< readings short of the map's range by more than the margin
  std::size_t unknown_hits = 0;
  double unknown_exposure_m = 0.0;
  /// m, unknown_exposure_m / unknown_hits; 0 when nothing was hit there.
  double unknown_free_path = 0.0;
  std::size_t band_hits = 0;
  std::size_t static_band_hits = 0;  ///< of band_hits: on something that stays
  double band_exposure_m = 0.0;
  double mean_width_m = 0.0;  ///< the clutter kinds' mean width at a uniform yaw
  /// static objects per m², static_band_hits / (band_exposure_m × mean_width_m); 0 without
  /// exposure. The other band hits are people passing (the crowd's, not the clutter's).
  double density = 0.0;
};

/// The log's reference in the window (log times from_s to to_s, compared with the poses'
/// stamps), in the map's frame M (X_MW), one point per 0.1 m driven: the route whose band the
/// clutter lies in.
std::vector<core::Vec2> RouteInMap(const std::vector<io::StampedPose>& reference,
                                   const core::Pose2& X_MW, double from_stamp, double to_stamp);

/// The map with its unknown cells within the clutter's corridor of the route (robot radius +
/// clutter.clearance) made known free: the robot drove there, so whatever the map does not
/// know, that much was empty. The simulated world and the calibration's walk both use it.
core::OccupancyGrid ClearedAlongRoute(core::OccupancyGrid grid,
                                      const std::vector<core::Vec2>& route,
                                      const ClutterConfig& clutter);

/// Fits the beams: a reading is short when below map_range − margin (m). Readings beyond
/// map_range + far_margin (m) are left out (random readings, the map wrong there); beams without
/// a return count as rays that passed everything up to map_range.
UnmappedFit FitUnmapped(std::span<const UnmappedBeam> beams, double margin, double far_margin,
                        double mean_width);

}  // namespace retrace::bench
