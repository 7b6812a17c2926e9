#include "nav/cluster_estimate.hpp"

#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>

#include "core/angle.hpp"

namespace retrace::nav {
namespace {

// Weighted mean of the particles within kClusterRadius and kClusterAngle of `around`.
std::optional<ClusterMean> LocalMean(std::span<const Particle> particles,
                                     const core::Pose2& around) {
  double x = 0.0, y = 0.0, s = 0.0, c = 0.0, total = 0.0;
  for (const Particle& p : particles) {
    const double dx = p.X_MR.x - around.x, dy = p.X_MR.y - around.y;
    if (dx * dx + dy * dy > kClusterRadius * kClusterRadius ||
        std::abs(core::AngleDiff(p.X_MR.theta, around.theta)) > kClusterAngle) {
      continue;
    }
    x += p.weight * p.X_MR.x;
    y += p.weight * p.X_MR.y;
    s += p.weight * std::sin(p.X_MR.theta);
    c += p.weight * std::cos(p.X_MR.theta);
    total += p.weight;
  }
  if (!(total > 0.0)) return std::nullopt;
  return ClusterMean{core::Pose2(x / total, y / total, std::atan2(s, c)), total};
}

}  // namespace

std::optional<ClusterMean> ClusterAround(std::span<const Particle> particles,
                                         const core::Pose2& around) {
  std::optional<ClusterMean> mean;
  core::Pose2 at = around;
  for (int iteration = 0; iteration < 3; ++iteration) {
    const std::optional<ClusterMean> m = LocalMean(particles, at);
    if (!m) break;
    mean = m;
    at = m->X_MR;
  }
  return mean;
}

std::optional<ClusterMean> MainCluster(std::span<const Particle> particles) {
  if (particles.empty()) return std::nullopt;
  constexpr double kBinXy = 0.5;
  constexpr int kHeadingBins = 12;  // 30 deg
  const double bin_theta = 2.0 * core::kPi / kHeadingBins;
  using Key = std::tuple<std::int64_t, std::int64_t, std::int64_t>;
  struct Bin {
    double weight = 0.0;
    std::size_t first = 0;  // a particle of the bin, for the seed
  };
  std::map<Key, Bin> bins;
  for (std::size_t j = 0; j < particles.size(); ++j) {
    const core::Pose2& X = particles[j].X_MR;
    const auto heading = static_cast<std::int64_t>(std::floor(X.theta / bin_theta));
    const Key key{static_cast<std::int64_t>(std::floor(X.x / kBinXy)),
                  static_cast<std::int64_t>(std::floor(X.y / kBinXy)),
                  ((heading % kHeadingBins) + kHeadingBins) % kHeadingBins};
    auto [it, inserted] = bins.try_emplace(key, Bin{0.0, j});
    it->second.weight += particles[j].weight;
  }
  const Bin* best = nullptr;
  double best_weight = -1.0;
  for (const auto& [key, bin] : bins) {
    const auto [bx, by, bt] = key;
    double sum = 0.0;
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dt = -1; dt <= 1; ++dt) {
          const auto it = bins.find({bx + dx, by + dy, (bt + dt + kHeadingBins) % kHeadingBins});
          if (it != bins.end()) sum += it->second.weight;
        }
      }
    }
    if (sum > best_weight) {
      best_weight = sum;
      best = &bin;
    }
  }
  const core::Pose2 seed = particles[best->first].X_MR;
  const std::optional<ClusterMean> mean = ClusterAround(particles, seed);
  return mean ? mean : std::optional<ClusterMean>(ClusterMean{seed, 0.0});
}

double ParticleSpread(std::span<const Particle> particles) {
  double w = 0.0, x = 0.0, y = 0.0;
  for (const Particle& p : particles) {
    w += p.weight;
    x += p.weight * p.X_MR.x;
    y += p.weight * p.X_MR.y;
  }
  if (!(w > 0.0)) return 0.0;
  x /= w;
  y /= w;
  double sum = 0.0;
  for (const Particle& p : particles) {
    const double dx = p.X_MR.x - x, dy = p.X_MR.y - y;
    sum += p.weight * (dx * dx + dy * dy);
  }
  return std::sqrt(sum / w);
}

}  // namespace retrace::nav
