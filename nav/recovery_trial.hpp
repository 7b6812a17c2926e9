#pragma once
// Recovery for a repeating robot (docs/METHOD.md, "Recovery"): when the belief explains the
// scans much worse than it used to (w_fast < trigger_ratio · w_slow), the localizer does not
// throw random particles into its belief, where one lucky fit over a single update can carry the
// estimate tens of metres away. It starts a *trial*: a second, small particle filter whose
// hypotheses lie where a repeating robot can be (near the estimate, and at the taught poses of the
// maps the route graph reaches within max_sigma of it: RouteGraph::PosesInReach), moved by the same motion model and weighted by the
// same beams. The two filters are compared by their evidence, the log of the belief-weighted
// likelihood of each scan, summed over the updates since the trial began (a log Bayes factor).
// Only when the trial has explained at least `confirm_updates` scans and beats the belief by
// `margin` nats does it replace the belief: a re-acquisition supported by several updates. A
// trial that has not won after `max_updates` ends.

#include <optional>
#include <span>
#include <vector>

#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "core/twist.hpp"
#include "nav/cluster_estimate.hpp"
#include "nav/likelihood_field.hpp"
#include "nav/motion_model.hpp"
#include "nav/particle.hpp"
#include "nav/measurement_model.hpp"

namespace retrace::nav {

/// The trial's hypotheses and its running log Bayes factor against the belief.
class RecoveryTrial {
 public:
  /// Starts a trial with these hypotheses (M), equally weighted.
  void Start(std::vector<core::Pose2> hypotheses);
  void Stop();
  bool running() const { return !hypotheses_.empty(); }

  /// Moves every hypothesis by one odometry increment with the sample motion model.
  void Predict(const core::OdometryDelta& delta, const MotionNoise& noise, core::Rng& rng);
  /// Weighs the hypotheses with the update's points (L frame, as the belief's: same model), adds
  /// this scan's evidence minus the belief's `belief_evidence` to the log Bayes factor, and
  /// resamples the hypotheses (low variance) when their effective sample size falls below half.
  /// The scan counts as explained (updates()) only with at least `min_points` end points: a few
  /// beams fit many places.
  void Weigh(const LikelihoodField& field, const core::Pose2& X_RL, const WeighedPoints& points,
             double belief_evidence, int min_points, core::Rng& rng);

  /// Scans explained since Start (weighed with at least min_points end points).
  int updates() const { return updates_; }
  /// Scans weighed since Start.
  int weighed() const { return weighed_; }
  /// Σ over those updates of (log evidence of the trial − log evidence of the belief), nats.
  double log_bayes_factor() const { return log_bayes_factor_; }
  /// The trial's main cluster (nav/cluster_estimate.hpp): its mean, and its share of the weight,
  /// near 1 when the hypotheses agree on one place, lower while two places still explain the
  /// scans alike. nullopt before Start.
  std::optional<ClusterMean> Main() const;
  /// The trial's particles drawn to `count` by weight (low variance), equally weighted.
  std::vector<Particle> Draw(std::size_t count, core::Rng& rng) const;

 private:
  std::vector<core::Pose2> hypotheses_;
  std::vector<double> weights_;
  int updates_ = 0;
  int weighed_ = 0;
  double log_bayes_factor_ = 0.0;
};

}  // namespace retrace::nav
