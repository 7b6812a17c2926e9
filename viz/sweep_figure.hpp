#pragma once
// sweep.png: a grid of small charts, one row per metric and one column per varied parameter,
// each showing the metric against the parameter with the spread over repeats. Plain data in
// (std only): the harness reads results.csv and groups its rows by combination.

#include <filesystem>
#include <string>
#include <vector>

#include "viz/figures.hpp"

namespace retrace::viz {

/// One parameter combination of a sweep and the metric values of its repeats.
struct SweepCombination {
  /// One value per SweepFigureData::parameters, as written in results.csv: a number ("300",
  /// "0.05"), "true"/"false" or a word ("partial").
  std::vector<std::string> values;
  /// metrics[k][r]: metric k of repeat r; one vector per SweepFigureData::metrics (repeats may
  /// differ in number between combinations); NaN where the metric is not available.
  std::vector<std::vector<double>> metrics;
};

struct SweepFigureData {
  std::vector<std::string> parameters;  ///< varied config keys, one column of panels each
  std::vector<std::string> metrics;     ///< metric names, one row of panels each
  std::vector<SweepCombination> combinations;
};

/// The most series (lines) a panel shows; with more combinations of the other parameters
/// they are pooled into one series whose bars span all of them.
inline constexpr int kMaxSweepSeries = 8;

/// Renders sweep.png. Panel (metric m, parameter p) is named "<m> vs <p>"; its frame is
/// (x, metric value) where x is
///   - the parameter's value when every value is a number (linear axis),
///   - log10 of the value when every value is a number > 0 and they span a factor >= 10,
///   - the index 0, 1, ... of the value in category order otherwise (false before true;
///     words in order of first appearance).
/// In each panel one series per combination of the other varied parameters: points at the
/// mean over repeats, bars from min to max over repeats, sorted along x and joined by lines;
/// series side by side at one x are moved a few pixels apart so their bars do not overlap.
/// With more than kMaxSweepSeries series they are pooled into one (mean, min and max over
/// every case at that x). Random sampling gives a scatter of every case instead (no lines,
/// no means) when there are several series and either none has two x values or more than half
/// of the combinations have an x value of their own (in a grid each x value is shared by
/// every combination of the others). NaN values are left out and counted in the panel title.
///
/// `options.width` is the figure width, widened to at least 320 px per parameter column;
/// `options.supersample` is not used (nothing is drawn in world space); an empty
/// `options.title` gives "Parameter sweep". Throws core::ConfigError for bad options,
/// core::IoError when there is no parameter, metric or combination, when a combination's
/// values or metrics do not match the names, or when the file cannot be written.
FigureInfo RenderSweepFigure(const SweepFigureData& data, const std::filesystem::path& png,
                             const FigureOptions& options = {});

}  // namespace retrace::viz
