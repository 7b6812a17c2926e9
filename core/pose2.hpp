#pragma once
// SE(2) poses. Notation (docs/DESIGN.md §2): X_AB is the pose of frame B expressed in frame A, and
// X_AC = X_AB * X_BC.

#include <Eigen/Core>
#include <iosfwd>

#include "core/angle.hpp"

namespace retrace::core {

using Vec2 = Eigen::Vector2d;

/// A rigid transform in the plane: translation (m) and heading (rad, kept in [-pi, pi)).
struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;

  Pose2() = default;
  Pose2(double x_in, double y_in, double theta_in) : x(x_in), y(y_in), theta(WrapAngle(theta_in)) {}

  static Pose2 Identity() { return {}; }

  Vec2 translation() const { return {x, y}; }

  /// X_AC = X_AB * X_BC.
  Pose2 operator*(const Pose2& X_BC) const;
  /// Maps a point expressed in B into A.
  Vec2 operator*(const Vec2& p_B) const;
  /// X_BA from X_AB.
  Pose2 Inverse() const;

  bool operator==(const Pose2&) const = default;
};

/// A pose with its rotation computed once, for mapping many points: PoseTransform(X)(p) is
/// X * p bit for bit (Pose2::operator* computes cos and sin on every call).
class PoseTransform {
 public:
  explicit PoseTransform(const Pose2& X);
  Vec2 operator()(const Vec2& p_B) const {
    return {x_ + c_ * p_B.x() - s_ * p_B.y(), y_ + s_ * p_B.x() + c_ * p_B.y()};
  }

 private:
  double x_, y_, c_, s_;
};

/// Interpolates on SE(2) along the straight line in translation and the shortest arc in
/// heading; t = 0 gives a, t = 1 gives b.
Pose2 Interpolate(const Pose2& a, const Pose2& b, double t);

/// Relative motion X_AB^-1 * X_AC: where C is seen from B.
inline Pose2 Between(const Pose2& X_AB, const Pose2& X_AC) { return X_AB.Inverse() * X_AC; }

/// Euclidean distance between the translations (m).
double Distance(const Pose2& a, const Pose2& b);

std::ostream& operator<<(std::ostream& os, const Pose2& p);

}  // namespace retrace::core
