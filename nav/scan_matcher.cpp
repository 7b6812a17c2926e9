#include "nav/scan_matcher.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "core/angle.hpp"
#include "core/errors.hpp"

namespace retrace::nav {

void ScanMatcherConfig::Validate() const {
  core::RequirePositive("match_range", match_range);
  core::RequirePositive("voxel_size", voxel_size);
  core::RequireNonNegative("point_spacing", point_spacing);
  core::RequirePositive("max_distance", max_distance);
  core::RequirePositive("sigma", sigma);
  core::RequireInRange("max_iterations", max_iterations, 1.0, 100.0);
  if (min_points < 3) {
    throw core::ConfigError("min_points", "must be >= 3, got " + std::to_string(min_points));
  }
  core::RequireInRange("min_inlier_fraction", min_inlier_fraction, 0.0, 1.0);
  core::RequireNonNegative("min_constraint", min_constraint);
  core::RequirePositive("max_correction", max_correction);
  core::RequirePositive("max_correction_deg", max_correction_deg);
  core::RequireInRange("max_correction_deg", max_correction_deg, 0.0, 45.0);
}

ScanMatcher::ScanMatcher(const ScanMatcherConfig& config, const RobotGeometry& robot)
    : config_(config), robot_(robot) {
  config_.Validate();
  robot_.Validate();
  search_cell_ = std::max(config_.max_distance, 4.0 * config_.voxel_size);
}

std::uint64_t ScanMatcher::Key(int x, int y) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) |
         static_cast<std::uint32_t>(y);
}

void ScanMatcher::KeepPoints(const core::LaserScan& scan, std::vector<core::Vec2>* points_R) const {
  points_R->clear();
  const double range_max = std::min(config_.match_range, robot_.range_max);
  core::Vec2 last(std::numeric_limits<double>::infinity(), 0.0);
  const core::PoseTransform X_RL(robot_.X_RL);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const double r = scan.ranges[i];
    if (!scan.Valid(i) || r < robot_.range_min || r > range_max) continue;
    const double a = scan.Angle(i);
    const core::Vec2 p_R = X_RL(core::Vec2(r * std::cos(a), r * std::sin(a)));
    if ((p_R - last).norm() < config_.point_spacing) continue;
    points_R->push_back(p_R);
    last = p_R;
  }
}

void ScanMatcher::AddScan(const core::LaserScan& scan, const core::Pose2& X_MR) {
  const double range_max = std::min(config_.match_range, robot_.range_max);
  const core::PoseTransform X_RL(robot_.X_RL), X_MR_map(X_MR);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const double r = scan.ranges[i];
    if (!scan.Valid(i) || r < robot_.range_min || r > range_max) continue;
    const double a = scan.Angle(i);
    const core::Vec2 p = X_MR_map(X_RL(core::Vec2(r * std::cos(a), r * std::sin(a))));
    const int vx = static_cast<int>(std::floor(p.x() / config_.voxel_size));
    const int vy = static_cast<int>(std::floor(p.y() / config_.voxel_size));
    const auto [it, inserted] =
        voxel_index_.try_emplace(Key(vx, vy), static_cast<std::uint32_t>(voxels_.size()));
    if (inserted) {
      voxels_.emplace_back();
      const int cx = static_cast<int>(std::floor(p.x() / search_cell_));
      const int cy = static_cast<int>(std::floor(p.y() / search_cell_));
      search_cells_[Key(cx, cy)].push_back(it->second);
    }
    Voxel& v = voxels_[it->second];
    v.sum_x += p.x();
    v.sum_y += p.y();
    ++v.count;
    v.mean = core::Vec2(v.sum_x / v.count, v.sum_y / v.count);
  }
}

void ScanMatcher::Clear() {
  voxels_.clear();
  voxel_index_.clear();
  search_cells_.clear();
}

bool ScanMatcher::Pair(const core::Vec2& p_M, Pairing* pairing) const {
  // Candidates: the map points of the 3×3 search cells around p (each cell at least
  // max_distance wide, so every point within max_distance is among them).
  const int cx = static_cast<int>(std::floor(p_M.x() / search_cell_));
  const int cy = static_cast<int>(std::floor(p_M.y() / search_cell_));
  near_.clear();
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const auto it = search_cells_.find(Key(cx + dx, cy + dy));
      if (it == search_cells_.end()) continue;
      for (std::uint32_t v : it->second) near_.push_back(voxels_[v].mean);
    }
  }
  double best = config_.max_distance * config_.max_distance;
  const core::Vec2* q = nullptr;
  for (const core::Vec2& c : near_) {
    const double d2 = (c - p_M).squaredNorm();
    if (d2 < best) {
      best = d2;
      q = &c;
    }
  }
  if (q == nullptr) return false;
  pairing->q = *q;
  // The local line: principal axis of the map points within 3 voxels of q.
  const double radius2 = 9.0 * config_.voxel_size * config_.voxel_size;
  core::Vec2 mean = core::Vec2::Zero();
  int n = 0;
  for (const core::Vec2& c : near_) {
    if ((c - *q).squaredNorm() <= radius2) {
      mean += c;
      ++n;
    }
  }
  pairing->normal = core::Vec2::Zero();
  if (n < 3) return true;
  mean /= n;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const core::Vec2& c : near_) {
    if ((c - *q).squaredNorm() <= radius2) cov += (c - mean) * (c - mean).transpose();
  }
  // The eigenvalues of the symmetric 2×2 covariance in closed form, and the eigenvector of the
  // smaller one: a line when the spread across is small against the spread along it.
  const double a = cov(0, 0), b = cov(0, 1), d = cov(1, 1);
  const double half_trace = 0.5 * (a + d);
  const double root = std::hypot(0.5 * (a - d), b);
  const double small = half_trace - root, large = half_trace + root;
  if (small < 0.1 * large) {
    // (b, small - a) and (small - d, b) are both eigenvectors of `small`; the longer is stabler.
    const core::Vec2 v1(b, small - a), v2(small - d, b);
    const core::Vec2 v = v1.squaredNorm() >= v2.squaredNorm() ? v1 : v2;
    const double norm = v.norm();
    if (norm > 0.0) pairing->normal = v / norm;
  }
  return true;
}

bool ScanMatcher::RepairDue(const core::Pose2& X,
                            const std::optional<core::Pose2>& paired_at) const {
  return !paired_at ||
         (core::Vec2(X.x, X.y) - core::Vec2(paired_at->x, paired_at->y)).norm() +
                 config_.match_range * std::abs(core::AngleDiff(X.theta, paired_at->theta)) >
             0.1 * config_.voxel_size;
}

void ScanMatcher::Linearize(const core::Pose2& X, bool repair, NormalEquations* eq) {
  eq->H.setZero();
  eq->b.setZero();
  eq->paired = 0;
  eq->inliers = 0;
  const double c = std::cos(X.theta);
  const double s = std::sin(X.theta);
  for (std::size_t i = 0; i < points_R_.size(); ++i) {
    const core::Vec2& p_R = points_R_[i];
    const core::Vec2 r(c * p_R.x() - s * p_R.y(), s * p_R.x() + c * p_R.y());
    const core::Vec2 p(X.x + r.x(), X.y + r.y());
    if (repair) paired_[i] = Pair(p, &pairings_[i]);
    if (!paired_[i]) continue;
    const Pairing& pairing = pairings_[i];
    ++eq->paired;
    const core::Vec2 e = p - pairing.q;
    const core::Vec2 dr(-r.y(), r.x());  // d(R p_R)/dθ
    auto add = [&](const core::Vec2& n, double residual) {
      const double a = std::abs(residual);
      const double weight = a <= config_.sigma ? 1.0 : config_.sigma / a;
      const Eigen::Vector3d J(n.x(), n.y(), n.dot(dr));
      eq->H.noalias() += weight * J * J.transpose();
      eq->b += weight * J * residual;
      return a;
    };
    if (pairing.normal.isZero()) {
      // No line around the partner (a pole, a corner): fit to the point itself.
      add(core::Vec2(1.0, 0.0), e.x());
      add(core::Vec2(0.0, 1.0), e.y());
      if (e.norm() <= 3.0 * config_.sigma) ++eq->inliers;
    } else if (add(pairing.normal, pairing.normal.dot(e)) <= 3.0 * config_.sigma) {
      ++eq->inliers;
    }
  }
}

MatchVerdict ScanMatcher::Judge(const ScanMatch& result, const core::Pose2& X,
                                const core::Pose2& X_MR_predicted) const {
  if (result.paired < config_.min_points) return MatchVerdict::kFewPoints;
  if (result.min_constraint < config_.min_constraint) return MatchVerdict::kDegenerate;
  if (result.inliers < config_.min_inlier_fraction * result.paired ||
      (core::Vec2(X.x, X.y) - core::Vec2(X_MR_predicted.x, X_MR_predicted.y)).norm() >
          config_.max_correction ||
      std::abs(core::AngleDiff(X.theta, X_MR_predicted.theta)) >
          core::DegToRad(config_.max_correction_deg)) {
    return MatchVerdict::kPoorFit;
  }
  return MatchVerdict::kMatched;
}

ScanMatch ScanMatcher::Match(const core::LaserScan& scan, const core::Pose2& X_MR_predicted) {
  ScanMatch result;
  result.X_MR = X_MR_predicted;
  if (voxels_.empty()) {
    result.verdict = MatchVerdict::kEmptyMap;
    return result;
  }
  KeepPoints(scan, &points_R_);
  result.points = static_cast<int>(points_R_.size());

  // Pairs are found again only when an end point may have moved by more than a tenth of a voxel
  // since they were found: the last steps of the fit move by less, and keep their pairs.
  NormalEquations eq;
  pairings_.resize(points_R_.size());
  paired_.resize(points_R_.size());
  std::optional<core::Pose2> paired_at;
  const auto linearize = [&](const core::Pose2& X) {
    const bool repair = RepairDue(X, paired_at);
    if (repair) paired_at = X;
    Linearize(X, repair, &eq);
  };

  // Gauss-Newton.
  core::Pose2 X = X_MR_predicted;
  for (int it = 0; it < config_.max_iterations; ++it) {
    linearize(X);
    if (eq.paired < config_.min_points) break;
    // A little damping keeps the step finite along a direction the scan does not constrain;
    // whether the result is used then is decided below.
    Eigen::Matrix3d A = eq.H;
    A.diagonal().array() += 1e-6 * (1.0 + eq.H.trace());
    const Eigen::Vector3d delta = -A.ldlt().solve(eq.b);
    if (!delta.allFinite()) break;
    X = core::Pose2(X.x + delta.x(), X.y + delta.y(), X.theta + delta.z());
    if (delta.head<2>().norm() < 1e-4 && std::abs(delta.z()) < 1e-5) break;
  }
  linearize(X);
  result.paired = eq.paired;
  result.inliers = eq.inliers;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(eq.H.topLeftCorner<2, 2>());
  result.min_constraint = eig.eigenvalues()(0);
  result.max_constraint = eig.eigenvalues()(1);
  result.verdict = Judge(result, X, X_MR_predicted);
  if (result.verdict == MatchVerdict::kMatched) result.X_MR = X;
  return result;
}

}  // namespace retrace::nav
