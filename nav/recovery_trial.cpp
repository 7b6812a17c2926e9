#include "nav/recovery_trial.hpp"

#include <cmath>
#include <optional>

#include "core/check.hpp"
#include "nav/resampling.hpp"

namespace retrace::nav {

void RecoveryTrial::Start(std::vector<core::Pose2> hypotheses) {
  RETRACE_CHECK(!hypotheses.empty());
  hypotheses_ = std::move(hypotheses);
  weights_.assign(hypotheses_.size(), 1.0 / static_cast<double>(hypotheses_.size()));
  updates_ = 0;
  weighed_ = 0;
  log_bayes_factor_ = 0.0;
}

void RecoveryTrial::Stop() {
  hypotheses_.clear();
  weights_.clear();
  updates_ = 0;
  weighed_ = 0;
  log_bayes_factor_ = 0.0;
}

std::optional<ClusterMean> RecoveryTrial::Main() const {
  std::vector<Particle> particles(hypotheses_.size());
  for (std::size_t j = 0; j < hypotheses_.size(); ++j) particles[j] = {hypotheses_[j], weights_[j]};
  return MainCluster(particles);
}

void RecoveryTrial::Predict(const core::OdometryDelta& delta, const MotionNoise& noise,
                            core::Rng& rng) {
  for (core::Pose2& X : hypotheses_) X = SampleMotion(X, delta, noise, rng);
}

void RecoveryTrial::Weigh(const LikelihoodField& field, const core::Pose2& X_RL,
                          const WeighedPoints& points, double belief_evidence, int min_points,
                          core::Rng& rng) {
  RETRACE_CHECK(running());
  const std::size_t n = hypotheses_.size();
  std::vector<double> log_w(n), w(n);
  for (std::size_t j = 0; j < n; ++j) {
    log_w[j] = std::log(weights_[j]) + ScanLogLikelihood(field, hypotheses_[j] * X_RL, points);
  }
  const double evidence = NormalizeLogWeights(log_w, w);
  log_bayes_factor_ += evidence - belief_evidence;
  ++weighed_;
  if (static_cast<int>(points.size()) >= min_points) ++updates_;
  weights_ = std::move(w);
  if (EffectiveSampleSize(weights_) < 0.5 * static_cast<double>(n)) {
    const std::vector<std::size_t> idx = LowVarianceResample(weights_, n, rng);
    std::vector<core::Pose2> next(n);
    for (std::size_t m = 0; m < n; ++m) next[m] = hypotheses_[idx[m]];
    hypotheses_ = std::move(next);
    weights_.assign(n, 1.0 / static_cast<double>(n));
  }
}

std::vector<Particle> RecoveryTrial::Draw(std::size_t count, core::Rng& rng) const {
  RETRACE_CHECK(running() && count > 0);
  const std::vector<std::size_t> idx = LowVarianceResample(weights_, count, rng);
  std::vector<Particle> out(count);
  const double w = 1.0 / static_cast<double>(count);
  for (std::size_t m = 0; m < count; ++m) out[m] = {hypotheses_[idx[m]], w};
  return out;
}

}  // namespace retrace::nav
