#include "bench/engine/snapshot_capture.hpp"

#include <cmath>
#include <utility>

namespace retrace::bench {

int PedestrianBeams(const nav::LocalizerUpdate& update, const sim::LidarReading& reading) {
  int n = 0;
  for (std::size_t i = 0; i < update.beams.size(); ++i) {
    if (update.beams[i] != nav::BeamUse::kUnused &&
        reading.truth[i].source == sim::BeamSource::kPedestrian)
      ++n;
  }
  return n;
}

LocalizationSnapshot CaptureSnapshot(const nav::Localizer& localizer,
                                     const nav::LocalizerUpdate& update,
                                     const sim::LidarReading& reading, double time, int map_index,
                                     const core::Pose2& X_WR, const core::Pose2& X_MR_truth,
                                     std::vector<sim::DynamicCircle> pedestrians_W,
                                     double half_width, double resolution) {
  std::vector<std::uint8_t> pedestrian;
  for (std::size_t i = 0; i < update.beams.size(); ++i)
    pedestrian.push_back(reading.truth[i].source == sim::BeamSource::kPedestrian ? 1 : 0);
  LocalizationSnapshot s =
      CaptureSnapshot(localizer, update, reading.scan, pedestrian, time, map_index, X_WR,
                      X_MR_truth, std::move(pedestrians_W), half_width, resolution);
  s.pedestrian_beams = PedestrianBeams(update, reading);
  return s;
}

LocalizationSnapshot CaptureSnapshot(
    const nav::Localizer& localizer, const nav::LocalizerUpdate& update,
    const core::LaserScan& scan, const std::vector<std::uint8_t>& pedestrian, double time,
    int map_index, const core::Pose2& X_WR, const core::Pose2& X_MR_truth,
    std::vector<sim::DynamicCircle> pedestrians_W, double half_width, double resolution) {
  LocalizationSnapshot s;
  s.time = time;
  s.map_index = map_index;
  s.X_WR = X_WR;
  s.X_MR_truth = X_MR_truth;
  s.X_MR_estimate = localizer.Estimate();
  s.X_RL = localizer.robot().X_RL;
  s.pedestrians_W = std::move(pedestrians_W);
  for (const nav::Particle& p : localizer.particles()) {
    s.particles.push_back(p.X_MR);
    s.weights.push_back(p.weight);
  }
  s.scan = scan;
  for (std::size_t i = 0; i < update.beams.size(); ++i)
    s.beam_use.push_back(static_cast<std::uint8_t>(update.beams[i]));
  s.pedestrian = pedestrian;

  // The beam end points in L, of the tested beams, split by the rejection.
  std::vector<core::Vec2> all, kept;
  for (std::size_t i = 0; i < update.beams.size(); ++i) {
    if (update.beams[i] == nav::BeamUse::kUnused) continue;
    const double r = s.scan.ranges[i], a = s.scan.Angle(i);
    const core::Vec2 p_L(r * std::cos(a), r * std::sin(a));
    all.push_back(p_L);
    if (update.beams[i] == nav::BeamUse::kUsed) kept.push_back(p_L);
  }
  LikelihoodSlice& slice = s.likelihood;
  slice.resolution = resolution;
  const int half = static_cast<int>(std::lround(half_width / resolution));
  slice.size = 2 * half + 1;
  slice.theta = X_MR_truth.theta;
  slice.origin = X_MR_truth.translation() - core::Vec2(half * resolution, half * resolution);
  const nav::LikelihoodField& field = localizer.likelihood_field();
  for (int row = 0; row < slice.size; ++row) {
    for (int col = 0; col < slice.size; ++col) {
      const core::Pose2 X_MR(slice.origin.x() + col * resolution,
                             slice.origin.y() + row * resolution, slice.theta);
      const core::PoseTransform X_ML(X_MR * s.X_RL);
      float sum_all = 0.0f, sum_kept = 0.0f;
      for (const core::Vec2& p : all) sum_all += field.LogLikelihood(X_ML(p));
      for (const core::Vec2& p : kept) sum_kept += field.LogLikelihood(X_ML(p));
      slice.all_beams.push_back(sum_all);
      slice.static_beams.push_back(sum_kept);
    }
  }
  return s;
}

}  // namespace retrace::bench
