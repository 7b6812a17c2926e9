#pragma once
// The figure of `retrace calibrate-lidar`: the measured range errors z − z* of the calibration's
// beams against the fitted mixture's density of z − z* (the mixture averaged over the beams'
// expected ranges), near the wall on a linear scale and over the whole range on a log scale.

#include <string>

#include "bench/calibration/lidar_calibration.hpp"
#include "viz/range_error_figure.hpp"

namespace retrace::bench {

/// The panels "near" (|z − z*| up to max(6 σ_hit, 0.2 m), linear) and "all" (every finite
/// error, log10 density) of the whole window's fit. Densities are per beam, no-return beams
/// included in the count, so both integrate to 1 − z_max.
viz::RangeErrorFigureData RangeErrorFigureOf(const LidarCalibration& calibration,
                                             const std::string& subtitle);

}  // namespace retrace::bench
