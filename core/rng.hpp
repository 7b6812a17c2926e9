#pragma once
// Seedable, splittable pseudo-random numbers with their own samplers, so that results do not
// depend on the standard library's distributions (docs/DESIGN.md §3). Generator: xoshiro256**,
// seeded through SplitMix64.

#include <array>
#include <cstdint>
#include <string_view>

namespace retrace::core {

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0);

  /// An independent stream for a named component ("lidar", "odometry", ...). The child depends
  /// only on this generator's seed and the name, not on how many numbers were drawn.
  Rng Split(std::string_view name) const;
  /// An independent stream for the i-th member of a family (pedestrian i, run i).
  Rng Split(std::uint64_t index) const;

  std::uint64_t seed() const { return seed_; }

  std::uint64_t NextU64();
  /// Uniform in [0, 1).
  double Uniform();
  /// Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  /// Uniform integer in [0, n); n > 0.
  std::uint64_t UniformIndex(std::uint64_t n);
  /// Standard normal (Marsaglia polar method).
  double Normal();
  double Normal(double mean, double stddev) { return mean + stddev * Normal(); }
  bool Bernoulli(double p) { return Uniform() < p; }

 private:
  std::uint64_t seed_;
  std::array<std::uint64_t, 4> s_{};
  double spare_normal_ = 0.0;
  bool has_spare_ = false;
};

/// 64-bit FNV-1a hash, used to derive stream seeds from names and for determinism hashes.
std::uint64_t HashBytes(const void* data, std::size_t size,
                        std::uint64_t h = 0xcbf29ce484222325ULL);

}  // namespace retrace::core
