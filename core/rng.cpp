#include "core/rng.hpp"

#include <cmath>

#include "core/check.hpp"

namespace retrace::core {
namespace {

std::uint64_t SplitMix64(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t Mix(std::uint64_t a, std::uint64_t b) {
  std::uint64_t x = a ^ (b + 0x9e3779b97f4a7c15ULL + (a << 6) + (a >> 2));
  return SplitMix64(x);
}

}  // namespace

Rng::Rng(std::uint64_t seed) : seed_(seed) {
  std::uint64_t x = seed;
  for (auto& w : s_) w = SplitMix64(x);
}

Rng Rng::Split(std::string_view name) const {
  return Rng(Mix(seed_, HashBytes(name.data(), name.size())));
}

Rng Rng::Split(std::uint64_t index) const { return Rng(Mix(seed_, Mix(index, 0x5851f42d4c957f2dULL))); }

std::uint64_t Rng::UniformIndex(std::uint64_t n) {
  RETRACE_CHECK(n > 0);
  // Rejection sampling removes modulo bias.
  const std::uint64_t limit = UINT64_MAX - UINT64_MAX % n;
  std::uint64_t x = NextU64();
  while (x >= limit) x = NextU64();
  return x % n;
}

std::uint64_t HashBytes(const void* data, std::size_t size, std::uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ULL;
  }
  return h;
}

}  // namespace retrace::core
