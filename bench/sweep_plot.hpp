#pragma once
// sweep.png: each collected metric of a sweep against each varied parameter, with the spread
// over repeats, rendered by the project's renderer (viz).

#include <filesystem>
#include <string>
#include <vector>

namespace retrace::bench {

/// Reads a sweep's results.csv (header: case,combo,repeat,seed, then the varied parameters,
/// then the metrics; NaN written as "nan") and renders `png`. `parameters` and `metrics` name
/// the columns of each kind. Throws core::IoError for a file it cannot read or parse and
/// viz::RenderError when no off-screen context can be made.
void RenderSweepPlot(const std::filesystem::path& results_csv, const std::vector<std::string>& parameters,
                     const std::vector<std::string>& metrics, const std::filesystem::path& png,
                     const std::string& title);

}  // namespace retrace::bench
