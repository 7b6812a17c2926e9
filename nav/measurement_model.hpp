#pragma once
// The end points of one scan as a measurement update weighs them (docs/METHOD.md, "The
// class-conditional measurement model"). Two models share this form:
//
//   paper               the beams eq. (9) kept, each weighed by the likelihood field (eq. 5-6):
//                       log p_i = log p_lf(end_i)
//   class_conditional   every tested beam, each a mixture of its two classes (Akai, Morales &
//                       Murase, IROS 2018): it hit a mapped obstacle (prior π) or an unknown one,
//                       p_i = π p_lf(end_i) + u_i,  u_i = (1 - π) p_u(z_i)
//
// p_u, the density of a return from an obstacle the map does not hold, depends on the reading
// only: p_u(z) = λ exp(-λ z) / (1 - exp(-λ z_max)) on [0, z_max]. A person can only shorten a
// beam, so a beam that sees through a mapped wall at the estimate (nav/beam_evidence.hpp) cannot
// be unknown: its u_i is 0 and only the map explains it. A beam that ends in a cell the map never
// observed carries no evidence either way and is left out (Localizer::ClassifiedEndPoints).

#include <cstdint>
#include <vector>

#include "core/config.hpp"
#include "core/pose2.hpp"
#include "nav/likelihood_field.hpp"

namespace retrace::nav {

/// The measurement model of the localizer's updates.
enum class MeasurementModel : std::uint8_t {
  kPaper,             ///< dynamic scan point rejection (eq. 7-9), then eq. (5-6) on the kept beams
  kClassConditional,  ///< every beam a mixture of a mapped and an unknown obstacle
};

/// The class-conditional model's parameters.
struct ClassConditionalConfig {
  double mapped_prior = 0.5;      ///< π: the prior probability that a beam hit a mapped obstacle
  double lambda_unknown = 0.05;   ///< λ (1/m): how fast unknown obstacles grow rarer with range
  double unknown_threshold = 0.5;  ///< a beam is unknown (dynamic) when its posterior exceeds this

  template <class V>
  void Reflect(V& v) {
    v("mapped_prior", mapped_prior);
    v("lambda_unknown", lambda_unknown);
    v("unknown_threshold", unknown_threshold);
  }
  /// Throws core::ConfigError naming the key.
  void Validate() const;

  /// u = (1 - π) p_u(z) (1/m) for a reading z (m) of a sensor with maximum range range_max (m).
  double UnknownDensity(double z, double range_max) const;
};

/// End points in the LiDAR frame and, for the class-conditional model, each one's unknown-class
/// density u_i (empty for the paper's model).
struct WeighedPoints {
  std::vector<double> xs, ys;
  std::vector<double> unknown;  ///< u_i (1/m) per point; empty: the paper's model
  double mapped_prior = 1.0;    ///< π (1 for the paper's model)

  std::size_t size() const { return xs.size(); }
  bool empty() const { return xs.empty(); }
  void Add(double x, double y) {
    xs.push_back(x);
    ys.push_back(y);
  }
};

/// Σ_i log p_i of the points for a LiDAR at X_ML (M) in the field's map.
double ScanLogLikelihood(const LikelihoodField& field, const core::Pose2& X_ML,
                         const WeighedPoints& points);

/// Each point's posterior probability of the unknown class for a LiDAR at X_ML:
/// u_i / (π p_lf(end_i) + u_i). Requires the class-conditional model (unknown not empty).
std::vector<double> UnknownPosterior(const LikelihoodField& field, const core::Pose2& X_ML,
                                     const WeighedPoints& points);

}  // namespace retrace::nav

namespace retrace::core {
template <>
struct EnumTraits<nav::MeasurementModel> {
  static constexpr std::array<std::pair<nav::MeasurementModel, std::string_view>, 2> kNames{{
      {nav::MeasurementModel::kPaper, "paper"},
      {nav::MeasurementModel::kClassConditional, "class_conditional"},
  }};
};
}  // namespace retrace::core
