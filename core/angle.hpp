#pragma once

#include <cmath>
#include <numbers>

namespace retrace::core {

inline constexpr double kPi = std::numbers::pi;

/// Wraps an angle (rad) into [-pi, pi).
inline double WrapAngle(double a) {
  if (a >= -kPi && a < kPi) return a;
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a < 0.0) a += 2.0 * kPi;
  return a - kPi;
}

/// Signed smallest difference a - b (rad), in [-pi, pi).
inline double AngleDiff(double a, double b) { return WrapAngle(a - b); }

/// sin(h) / h, accurate near 0 (the chord factor of an arc).
inline double Sinc(double h) {
  if (std::abs(h) < 1e-4) return 1.0 - h * h / 6.0;
  return std::sin(h) / h;
}

inline constexpr double DegToRad(double deg) { return deg * kPi / 180.0; }
inline constexpr double RadToDeg(double rad) { return rad * 180.0 / kPi; }

}  // namespace retrace::core
