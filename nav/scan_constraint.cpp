#include "nav/scan_constraint.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

namespace retrace::nav {
namespace {

constexpr double kPointSpacing = 0.1;  // m, as the scan matcher keeps end points
constexpr double kNeighbourGap = 0.3;  // m: neighbours farther apart lie on different surfaces

}  // namespace

double ScanConstraint(const core::LaserScan& scan, const RobotGeometry& robot) {
  std::vector<core::Vec2> points;
  const core::PoseTransform X_RL(robot.X_RL);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (!scan.Valid(i)) continue;
    const double r = scan.ranges[i];
    const double a = scan.Angle(i);
    const core::Vec2 p = X_RL(core::Vec2(r * std::cos(a), r * std::sin(a)));
    if (!points.empty() && (p - points.back()).norm() < kPointSpacing) continue;
    points.push_back(p);
  }
  Eigen::Matrix2d H = Eigen::Matrix2d::Zero();
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    const core::Vec2 before = points[i] - points[i - 1];
    const core::Vec2 after = points[i + 1] - points[i];
    if (before.norm() > kNeighbourGap || after.norm() > kNeighbourGap) continue;
    const core::Vec2 tangent = (points[i + 1] - points[i - 1]).normalized();
    const core::Vec2 n(-tangent.y(), tangent.x());
    H += n * n.transpose();
  }
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(H).eigenvalues()(0);
}

}  // namespace retrace::nav
