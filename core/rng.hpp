#pragma once
// Seedable, splittable pseudo-random numbers with their own samplers, so that results do not
// depend on the standard library's distributions (docs/DESIGN.md §3). Generator: xoshiro256**,
// seeded through SplitMix64.

#include <array>
#include <cmath>
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

// The samplers are defined here so that they inline into the loops that draw millions of numbers
// (the LiDAR's noise, the motion model); the same operations as anywhere else.

inline std::uint64_t Rng::NextU64() {
  const auto rotl = [](std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); };
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

inline double Rng::Uniform() { return static_cast<double>(NextU64() >> 11) * 0x1.0p-53; }

inline double Rng::Normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_normal_;
  }
  double u = 0.0, v = 0.0, s = 0.0;
  do {
    u = 2.0 * Uniform() - 1.0;
    v = 2.0 * Uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double f = std::sqrt(-2.0 * std::log(s) / s);
  spare_normal_ = v * f;
  has_spare_ = true;
  return u * f;
}

/// 64-bit FNV-1a hash, used to derive stream seeds from names and for determinism hashes.
std::uint64_t HashBytes(const void* data, std::size_t size,
                        std::uint64_t h = 0xcbf29ce484222325ULL);

}  // namespace retrace::core
