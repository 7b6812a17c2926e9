#pragma once
// sweep.png: each collected metric of a sweep against each varied parameter, with the spread
// over repeats, rendered by the project's renderer (viz).

#include <filesystem>
#include <string>
#include <vector>

#include "viz/sweep_figure.hpp"

namespace retrace::bench {

/// Reads a sweep's results.csv strictly, as RenderSweepPlot does: one combination per combo
/// cell, in order of first appearance, with its parameter values as written and each metric's
/// value per repeat (NaN for "nan"). Throws core::IoError as RenderSweepPlot.
viz::SweepFigureData ReadSweepResults(const std::filesystem::path& results_csv,
                                      const std::vector<std::string>& parameters,
                                      const std::vector<std::string>& metrics);

/// Reads a sweep's results.csv (header: case,combo,repeat,seed, then the varied parameters,
/// then the metrics; NaN written as "nan") and renders `png` (viz::RenderSweepFigure: one row
/// of panels per metric, one column per parameter). `parameters` and `metrics` name the
/// columns of each kind; other columns are ignored. Rows with the same combo are the repeats
/// of one combination and must agree on every parameter value. Throws core::IoError for a
/// file it cannot read or parse ("<file>:<line>: ..."; a row with the wrong number of cells, a
/// missing column, a metric cell that is not a number or nan, a combo seen with two different
/// parameter values or a (combo, repeat) seen twice) or a PNG it cannot write; nothing is
/// written then. Never throws viz::RenderError (the figure is drawn without OpenGL).
void RenderSweepPlot(const std::filesystem::path& results_csv,
                     const std::vector<std::string>& parameters,
                     const std::vector<std::string>& metrics, const std::filesystem::path& png,
                     const std::string& title);

}  // namespace retrace::bench
