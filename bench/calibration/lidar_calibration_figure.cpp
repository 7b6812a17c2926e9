#include "bench/calibration/lidar_calibration_figure.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace retrace::bench {

namespace {

constexpr std::size_t kCurveBeams = 2000;  // beams the mixture is averaged over
constexpr int kCurvePoints = 600;

// The histogram of the finite errors in [lo, hi] in `bins` bins, as densities per beam.
void Histogram(const std::vector<double>& errors, std::size_t beams, double lo, double hi, int bins,
               viz::RangeErrorPanel* panel) {
  const double width = (hi - lo) / bins;
  panel->bin_edges.clear();
  for (int b = 0; b <= bins; ++b) panel->bin_edges.push_back(lo + b * width);
  panel->bin_density.assign(static_cast<std::size_t>(bins), 0.0);
  for (double e : errors) {
    if (e < lo || e > hi) continue;
    const auto b =
        std::min(static_cast<std::size_t>((e - lo) / width), static_cast<std::size_t>(bins - 1));
    panel->bin_density[b] += 1.0;
  }
  for (double& d : panel->bin_density) d /= static_cast<double>(beams) * width;
}

// The fitted density of z − z* over [lo, hi]: the mixture's density at z* + e averaged over
// evenly spaced beams.
void Curve(const LidarCalibration& c, double lo, double hi, viz::RangeErrorPanel* panel) {
  const auto& samples = c.beams.samples;
  const std::size_t step = std::max<std::size_t>(1, samples.size() / kCurveBeams);
  const nav::BeamMixture& m = c.whole.result.mixture;
  for (int k = 0; k <= kCurvePoints; ++k) {
    const double e = lo + (hi - lo) * k / kCurvePoints;
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < samples.size(); i += step, ++n) {
      const double z_star = samples[i].z_star;
      sum += nav::BeamMixtureDensity(m, z_star + e, z_star, c.beams.range_min, c.beams.range_max);
    }
    panel->curve_error.push_back(e);
    panel->curve_density.push_back(n > 0 ? sum / static_cast<double>(n) : 0.0);
  }
}

}  // namespace

viz::RangeErrorFigureData RangeErrorFigureOf(const LidarCalibration& calibration,
                                             const std::string& subtitle) {
  std::vector<double> errors;
  double lo = 0.0, hi = 0.0;
  for (const nav::BeamSample& s : calibration.beams.samples) {
    if (!std::isfinite(s.z)) continue;
    errors.push_back(s.z - s.z_star);
    lo = std::min(lo, errors.back());
    hi = std::max(hi, errors.back());
  }
  const std::size_t beams = calibration.beams.samples.size();
  const double sigma = calibration.whole.result.mixture.sigma_hit;
  const double near = std::max(6.0 * sigma, 0.2);
  viz::RangeErrorFigureData data;
  data.subtitle = subtitle;
  viz::RangeErrorPanel near_panel;
  near_panel.name = "near";
  near_panel.title = "Near the expected range (linear)";
  Histogram(errors, beams, -near, near, 80, &near_panel);
  Curve(calibration, -near, near, &near_panel);
  viz::RangeErrorPanel all;
  all.name = "all";
  all.title = "Every finite reading (log scale)";
  all.log_scale = true;
  hi = std::max(hi, lo + 1.0);
  Histogram(errors, beams, lo, hi, 120, &all);
  Curve(calibration, lo, hi, &all);
  data.panels = {std::move(near_panel), std::move(all)};
  return data;
}

}  // namespace retrace::bench
