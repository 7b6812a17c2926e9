#include "core/pose2.hpp"

#include <cmath>
#include <ostream>

namespace retrace::core {

Pose2 Pose2::operator*(const Pose2& X_BC) const {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  return {x + c * X_BC.x - s * X_BC.y, y + s * X_BC.x + c * X_BC.y, theta + X_BC.theta};
}

Vec2 Pose2::operator*(const Vec2& p_B) const { return PoseTransform(*this)(p_B); }

PoseTransform::PoseTransform(const Pose2& X)
    : x_(X.x), y_(X.y), c_(std::cos(X.theta)), s_(std::sin(X.theta)) {}

Pose2 Pose2::Inverse() const {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  return {-c * x - s * y, s * x - c * y, -theta};
}

Pose2 Interpolate(const Pose2& a, const Pose2& b, double t) {
  return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.theta + t * AngleDiff(b.theta, a.theta)};
}

double Distance(const Pose2& a, const Pose2& b) { return std::hypot(a.x - b.x, a.y - b.y); }

std::ostream& operator<<(std::ostream& os, const Pose2& p) {
  return os << "Pose2(" << p.x << ", " << p.y << ", " << p.theta << ")";
}

}  // namespace retrace::core
