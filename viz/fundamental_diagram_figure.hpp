#pragma once
// fundamental_diagram.png: walking speed against crowd density, a reference curve with a
// tolerance band and one or more series of simulated means with their spread (one-way and
// two-way flow, say). Plain data in (std only): the harness computes the curve and the points.

#include <filesystem>
#include <string>
#include <vector>

#include "viz/figures.hpp"

namespace retrace::viz {

/// One simulated density: mean speed and its standard deviation (m/s).
struct SpeedAtDensity {
  double density = 0.0;  ///< persons/m²
  double mean = 0.0;     ///< m/s
  double sd = 0.0;       ///< m/s
};

/// One series of simulated points, drawn in its own colour and marker.
struct SpeedSeries {
  std::string label = "simulated (mean, bars: +-1 SD)";
  std::vector<SpeedAtDensity> points;
};

struct FundamentalDiagramFigureData {
  std::vector<double> curve_density;  ///< persons/m², increasing
  std::vector<double> curve_speed;    ///< m/s, one per curve_density
  std::vector<double> band_low;       ///< m/s, lower edge of the band at each curve_density
  std::vector<double> band_high;      ///< m/s, upper edge
  std::string curve_label = "reference";
  std::string band_label = "tolerance band";
  std::vector<SpeedSeries> series;  ///< drawn in order, each in the next colour and marker
  std::string subtitle;
};

/// Renders fundamental_diagram.png: one panel "speed" whose frame is (density in persons/m²,
/// speed in m/s), the band filled, the curve as a line, each point as a marker with a bar of
/// +-1 SD (the series side by side, slightly apart in density). `options.supersample` is not
/// used; an empty `options.title` gives "Fundamental diagram". Throws core::ConfigError for bad
/// options, core::IoError when there is no curve or no point, when there are more than four
/// series, when the curve and band lengths differ, or when the file cannot be written.
FigureInfo RenderFundamentalDiagramFigure(const FundamentalDiagramFigureData& data,
                                          const std::filesystem::path& png,
                                          const FigureOptions& options = {});

}  // namespace retrace::viz
