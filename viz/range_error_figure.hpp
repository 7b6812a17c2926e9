#pragma once
// range_error.png (`retrace calibrate-lidar`): the measured range errors z − z* of a log's beams
// as a histogram against the density of the fitted beam mixture, in panels (e.g. around the
// wall on a linear scale, the whole range on a log scale). Plain data in (std only): the harness
// bins the errors and evaluates the mixture.

#include <filesystem>
#include <string>
#include <vector>

#include "viz/figures.hpp"

namespace retrace::viz {

/// One panel: a histogram (density per bin) and a curve over the same error axis.
struct RangeErrorPanel {
  std::string name;                   ///< PanelInfo name
  std::string title;                  ///< above the panel
  std::vector<double> bin_edges;      ///< m, increasing, one more than bin_density
  std::vector<double> bin_density;    ///< 1/m, measured
  std::vector<double> curve_error;    ///< m, increasing
  std::vector<double> curve_density;  ///< 1/m, fitted
  bool log_scale = false;             ///< y as log10 of the density; empty bins left out
};

struct RangeErrorFigureData {
  std::vector<RangeErrorPanel> panels;
  std::string histogram_label = "measured";
  std::string curve_label = "fitted mixture";
  std::string subtitle;
};

/// Renders the panels one above the other; a panel's frame is (error m, density 1/m or its
/// log10). An empty options.title gives "Range error: measured against the fitted beam model".
/// Throws core::ConfigError for bad options, core::IoError for no panel, a panel without bins or
/// curve or whose lengths disagree, or a file that cannot be written.
FigureInfo RenderRangeErrorFigure(const RangeErrorFigureData& data,
                                  const std::filesystem::path& png,
                                  const FigureOptions& options = {});

}  // namespace retrace::viz
