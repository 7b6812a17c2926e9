#pragma once
// The likelihood field of a map (paper eq. 5-6): an exact Euclidean distance transform of the
// occupied cells and a per-cell table of the log-likelihood of a beam end point, so that one
// beam evaluation is one table lookup. The untruncated distance field (m) is kept as well
// (the grid ray caster builds its own clearance grid from the occupancy for sphere tracing).

#include <cstdint>
#include <limits>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"

namespace retrace::nav {

/// Parameters of the likelihood-field measurement model (eq. 5-6).
///
///   p(d) = z_hit · exp(-d² / 2σ²) / (sqrt(2π) σ) + z_rand / range_max
///
/// d (m) is the distance from the beam end point's cell centre to the nearest occupied cell
/// centre minus half a cell (0 in occupied cells; a surface lies inside its cell, so the face a
/// beam meets is on average half a cell nearer than the centre, and without the correction the
/// field pulls end points into the wall cells), truncated at max_distance. p_hit is the 1-D normal
/// density of d (1/m), so that it is commensurable with the uniform density z_rand / range_max
/// (1/m) as in Probabilistic Robotics Table 6.3. Max-range readings (+inf) are not weighted at all,
/// so z_max does not appear. The default σ = 0.2 m covers a 0.1 m grid's quantisation (up to 0.07 m
/// to a cell centre), LiDAR noise (0.01-0.04 m) and the blur of odometry-built maps, while still
/// separating poses 0.1 m apart (the original implementation used about 0.28 m).
struct LikelihoodFieldConfig {
  double occupied_threshold = 0.65;  ///< a cell is occupied when its probability >= this
  double max_distance = 2.0;         ///< m, truncation of d in the likelihood table
  double sigma_hit = 0.2;            ///< m
  double z_hit = 0.9;
  double z_rand = 0.05;

  template <class V>
  void Reflect(V& v) {
    v("occupied_threshold", occupied_threshold);
    v("max_distance", max_distance);
    v("sigma_hit", sigma_hit);
    v("z_hit", z_hit);
    v("z_rand", z_rand);
  }
  /// Throws core::ConfigError naming the key (e.g. "sigma_hit").
  void Validate() const;
};

/// Exact Euclidean distance transform (Felzenszwalb-Huttenlocher, two passes) of a grid's
/// occupied cells, in cells: result[i] = distance (cells) from cell i's centre to the nearest
/// occupied cell centre, +inf when the grid has no occupied cell. `occupied` is row-major
/// (index y * width + x), width * height entries.
std::vector<float> DistanceTransformCells(const std::vector<std::uint8_t>& occupied, int width,
                                          int height);

/// A cell counts as observed (LikelihoodField::Known) when its probability is at least this, or
/// at most 1 minus this: a cell never observed holds 0.5 (log-odds 0), and one observed once
/// holds the inverse sensor model's free or occupied value, well outside this band.
inline constexpr double kKnownProbability = 0.55;

/// The likelihood field of one occupancy grid in its map frame M.
class LikelihoodField {
 public:
  /// Builds the occupancy mask, the distance field and the log-likelihood table of `map` for a
  /// sensor with maximum range range_max (m). Validates the config (throws core::ConfigError);
  /// throws core::ConfigError("range_max") unless range_max > 0. Keeps no reference to map.
  LikelihoodField(const core::OccupancyGrid& map, const LikelihoodFieldConfig& config,
                  double range_max);

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  const core::Vec2& origin() const { return origin_; }  ///< lower-left corner of cell (0, 0) in M
  const LikelihoodFieldConfig& config() const { return config_; }
  double range_max() const { return range_max_; }

  /// Log-likelihood (natural log of a density in 1/m) of a beam end point at p_M (M): the table
  /// value of its cell, or OutsideLogLikelihood() outside the map.
  float LogLikelihood(const core::Vec2& p_M) const {
    const double gx = (p_M.x() - origin_.x()) * inv_resolution_;
    const double gy = (p_M.y() - origin_.y()) * inv_resolution_;
    if (!(gx >= 0.0 && gy >= 0.0 && gx < width_d_ && gy < height_d_))
      return outside_log_likelihood_;
    return log_likelihood_[static_cast<std::size_t>(static_cast<int>(gy)) *
                               static_cast<std::size_t>(width_) +
                           static_cast<std::size_t>(static_cast<int>(gx))];
  }
  /// log(z_rand / range_max): the value of an end point outside the map (or very far from
  /// any obstacle).
  float OutsideLogLikelihood() const { return outside_log_likelihood_; }
  /// log p(d) of eq. 5-6 for a distance d (m), truncated at max_distance (the table holds
  /// LogLikelihoodOfDistance(max(0, distance - resolution / 2)) per cell).
  double LogLikelihoodOfDistance(double d) const;

  /// Sums LogLikelihood over end points given in the LiDAR frame L for a LiDAR at X_ML: the
  /// inner loop of the particle weighting (one rotation per call, one lookup per point).
  /// xs_L, ys_L: n end points (m, in L).
  double SumLogLikelihood(const core::Pose2& X_ML, const double* xs_L, const double* ys_L,
                          std::size_t n) const;
  /// Σ_i log(scale · exp(LogLikelihood(end_i)) + floor_i): the class-conditional mixture
  /// (nav/measurement_model.hpp) with the same cell arithmetic as SumLogLikelihood. floor: n densities
  /// (1/m), each >= 0; scale > 0.
  double SumLogMixture(const core::Pose2& X_ML, const double* xs_L, const double* ys_L,
                       const double* floor, double scale, std::size_t n) const;

  /// Distance (m) from each cell centre to the nearest occupied cell centre, untruncated; +inf
  /// when the map has no occupied cell.
  const std::vector<float>& distance() const { return distance_; }
  /// 1 where the cell is occupied (probability >= occupied_threshold), else 0.
  const std::vector<std::uint8_t>& occupied() const { return occupied_; }
  bool Occupied(core::CellIndex c) const {
    return occupied_[static_cast<std::size_t>(c.y) * static_cast<std::size_t>(width_) +
                     static_cast<std::size_t>(c.x)] != 0;
  }
  /// The cell holding p_M (M) was observed by the mapper (its probability lies outside
  /// [1 - kKnownProbability, kKnownProbability]); false outside the map.
  bool Known(const core::Vec2& p_M) const {
    const double gx = (p_M.x() - origin_.x()) * inv_resolution_;
    const double gy = (p_M.y() - origin_.y()) * inv_resolution_;
    if (!(gx >= 0.0 && gy >= 0.0 && gx < width_d_ && gy < height_d_)) return false;
    const std::size_t row = static_cast<std::size_t>(static_cast<int>(gy));
    return known_[row * static_cast<std::size_t>(width_) +
                  static_cast<std::size_t>(static_cast<int>(gx))] != 0;
  }
  /// Distance (m) from the cell holding p_M to the nearest occupied cell; +inf outside the map.
  float DistanceAt(const core::Vec2& p_M) const {
    const double gx = (p_M.x() - origin_.x()) * inv_resolution_;
    const double gy = (p_M.y() - origin_.y()) * inv_resolution_;
    if (!(gx >= 0.0 && gy >= 0.0 && gx < width_d_ && gy < height_d_))
      return std::numeric_limits<float>::infinity();
    return distance_[static_cast<std::size_t>(static_cast<int>(gy)) *
                         static_cast<std::size_t>(width_) +
                     static_cast<std::size_t>(static_cast<int>(gx))];
  }
  float Distance(core::CellIndex c) const {
    return distance_[static_cast<std::size_t>(c.y) * static_cast<std::size_t>(width_) +
                     static_cast<std::size_t>(c.x)];
  }

 private:
  // Σ_i term(i, table value of end point i) for a LiDAR at X_ML (requires a table).
  template <class Term>
  double SumOverEndPoints(const core::Pose2& X_ML, const double* xs_L, const double* ys_L,
                          std::size_t n, Term term) const;

  LikelihoodFieldConfig config_;
  double range_max_ = 0.0;
  int width_ = 0;
  int height_ = 0;
  double width_d_ = 0.0;
  double height_d_ = 0.0;
  double resolution_ = 0.0;
  double inv_resolution_ = 0.0;
  core::Vec2 origin_ = core::Vec2::Zero();
  float outside_log_likelihood_ = 0.0f;
  std::vector<std::uint8_t> occupied_;
  std::vector<std::uint8_t> known_;
  std::vector<float> distance_;
  std::vector<float> log_likelihood_;
};

}  // namespace retrace::nav
