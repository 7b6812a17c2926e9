#include "nav/localizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <unordered_set>
#include <utility>

#include "core/angle.hpp"
#include "core/check.hpp"
#include "core/errors.hpp"
#include "nav/cluster_estimate.hpp"
#include "nav/dynamic_beam_test.hpp"
#include "nav/resampling.hpp"

namespace retrace::nav {
namespace {

// Runs a nested Validate() and prefixes the key path of its ConfigError.
template <class T>
void ValidateNested(const std::string& prefix, const T& nested) {
  try {
    nested.Validate();
  } catch (const core::ConfigError& e) {
    throw core::ConfigError(prefix + "." + e.key_path(), e.detail());
  }
}

// KLD bound (Fox 2003, eq. 12) for k occupied bins.
double KldBound(int k, double epsilon, double z) {
  if (k <= 1) return 1.0;
  const double km1 = k - 1;
  const double a = 2.0 / (9.0 * km1);
  const double b = 1.0 - a + std::sqrt(a) * z;
  return km1 / (2.0 * epsilon) * b * b * b;
}

// The belief's spread at a scan's endpoints (m): the prior-weighted RMS distance of the particles
// from their mean position plus the mean tested range times the RMS heading difference from their
// circular mean, i.e. how far apart the particles put a typical beam's endpoint.
double EndpointSpread(std::span<const core::Pose2> X, std::span<const double> prior,
                      double mean_range) {
  double total = 0.0, mx = 0.0, my = 0.0, mc = 0.0, ms = 0.0;
  for (std::size_t j = 0; j < X.size(); ++j) {
    total += prior[j];
    mx += prior[j] * X[j].x;
    my += prior[j] * X[j].y;
    mc += prior[j] * std::cos(X[j].theta);
    ms += prior[j] * std::sin(X[j].theta);
  }
  if (!(total > 0.0)) return std::numeric_limits<double>::infinity();
  mx /= total;
  my /= total;
  const double mean_theta = std::atan2(ms, mc);
  double var_xy = 0.0, var_theta = 0.0;
  for (std::size_t j = 0; j < X.size(); ++j) {
    const double dx = X[j].x - mx, dy = X[j].y - my;
    const double dtheta = core::AngleDiff(X[j].theta, mean_theta);
    var_xy += prior[j] * (dx * dx + dy * dy);
    var_theta += prior[j] * dtheta * dtheta;
  }
  return std::sqrt(var_xy / total) + mean_range * std::sqrt(var_theta / total);
}

// The particles in the sums of eq. (9) (DynamicRejectionConfig::particles): all with their prior
// weights when `count` is 0 or there are at most `count` of positive weight, else a sample of
// `count` drawn by prior weight (the comb at (k + 1/2) / count), each distinct particle weighted
// by how often it was drawn.
void StratifiedSample(std::span<const core::Pose2> X, std::span<const double> prior, int count,
                      std::vector<core::Pose2>* sample_X, std::vector<double>* sample_w) {
  double total = 0.0;
  std::size_t positive = 0;
  for (const double w : prior) {
    total += w;
    positive += w > 0.0 ? 1 : 0;
  }
  sample_X->clear();
  sample_w->clear();
  if (count == 0 || positive <= static_cast<std::size_t>(count) || !(total > 0.0)) {
    sample_X->assign(X.begin(), X.end());
    sample_w->assign(prior.begin(), prior.end());
    return;
  }
  std::vector<double> normalized(prior.begin(), prior.end());
  for (double& w : normalized) w /= total;
  const std::vector<std::size_t> drawn =
      LowVarianceResampleWithOffset(normalized, static_cast<std::size_t>(count), 0.5);
  for (std::size_t k = 0; k < drawn.size(); ++k) {  // indices come in increasing order
    if (k > 0 && drawn[k] == drawn[k - 1]) {
      sample_w->back() += 1.0;
    } else {
      sample_X->push_back(X[drawn[k]]);
      sample_w->push_back(1.0);
    }
  }
}

}  // namespace

void DynamicRejectionConfig::Validate() const {
  core::RequireInRange("chi", chi, 0.0, 1.0);
  core::RequireIntInRange("particles", particles, 0, 1'000'000);
  ValidateNested("beam_model", beam_model);
}

void AugmentedMclConfig::Validate() const {
  core::RequireInRange("alpha_slow", alpha_slow, 0.0, 1.0);
  if (!(alpha_slow > 0.0)) throw core::ConfigError("alpha_slow", "must be > 0");
  core::RequireInRange("alpha_fast", alpha_fast, 0.0, 1.0);
  core::RequireGreater("alpha_fast", alpha_fast, "alpha_slow", alpha_slow);
  core::RequireInRange("trigger_ratio", trigger_ratio, 0.0, 1.0);
  core::RequirePositive("path_reach", path_reach);
  core::RequireNonNegative("reach_per_metre", reach_per_metre);
  core::RequireIntInRange("hypotheses", hypotheses, 1, 1'000'000);
  core::RequireInRange("near_fraction", near_fraction, 0.0, 1.0);
  core::RequireNonNegative("near_sigma_xy", near_sigma_xy);
  core::RequireNonNegative("near_sigma_theta", near_sigma_theta);
  core::RequireNonNegative("path_sigma_xy", path_sigma_xy);
  core::RequireNonNegative("path_sigma_theta", path_sigma_theta);
  core::RequireIntInRange("confirm_updates", confirm_updates, 1, 1'000'000);
  core::RequireIntInRange("min_beams", min_beams, 1, 1'000'000);
  core::RequireIntInRange("max_updates", max_updates, confirm_updates, 1'000'000);
  core::RequireNonNegative("margin", margin);
  core::RequireInRange("min_cluster_share", min_cluster_share, 0.0, 1.0);
  core::RequireNonNegative("jump_cost", jump_cost);
  core::RequireInRange("free_threshold", free_threshold, 0.0, 0.5);
  if (!(free_threshold < 0.5)) {
    throw core::ConfigError("free_threshold", "must be < 0.5 (unknown cells are 0.5)");
  }
}

void KldConfig::Validate() const {
  core::RequireIntInRange("min_particles", min_particles, 1, 10'000'000);
  core::RequireIntInRange("max_particles", max_particles, min_particles, 10'000'000);
  core::RequirePositive("epsilon", epsilon);
  core::RequirePositive("z_quantile", z_quantile);
  core::RequirePositive("bin_xy", bin_xy);
  core::RequirePositive("bin_theta_deg", bin_theta_deg);
}

void LocalizerConfig::Validate() const {
  core::RequireIntInRange("particles", particles, 1, 10'000'000);
  core::RequireIntInRange("beam_step", beam_step, 1, 1'000'000);
  core::RequireNonNegative("update_distance", update_distance);
  core::RequireNonNegative("update_angle_deg", update_angle_deg);
  core::RequireInRange("resample_ess_ratio", resample_ess_ratio, 0.0, 1.0);
  ValidateNested("motion", motion);
  ValidateNested("likelihood_field", likelihood_field);
  ValidateNested("rejection", rejection);
  ValidateNested("class_conditional", class_conditional);
  ValidateNested("augmented", augmented);
  ValidateNested("kld", kld);
  ValidateNested("reliability", reliability);
}

Localizer::Localizer(const LocalizerConfig& config, const RobotGeometry& robot, core::Rng rng)
    : config_(config), robot_(robot), rng_(rng), reliability_(config.reliability) {
  config_.Validate();
  robot_.Validate();
}

Localizer::~Localizer() = default;
Localizer::Localizer(Localizer&&) noexcept = default;
Localizer& Localizer::operator=(Localizer&&) noexcept = default;

const LikelihoodField& Localizer::likelihood_field() const {
  RETRACE_CHECK(field_ != nullptr);
  return *field_;
}

void Localizer::ResetAverages() {
  averages_started_ = false;
  w_slow_ = 0.0;
  w_fast_ = 0.0;
}

void Localizer::SetMap(const core::OccupancyGrid& map) {
  // Build the new field before dropping the caster that points into the old one.
  auto field = std::make_unique<LikelihoodField>(map, config_.likelihood_field, robot_.range_max);
  caster_ = std::make_unique<GridRayCaster>(*field);
  field_ = std::move(field);
  beam_model_ = std::make_unique<BeamModel>(config_.rejection.beam_model, robot_.range_max);
  free_cells_.clear();
  RETRACE_CHECK(map.log_odds().size() <= std::numeric_limits<std::uint32_t>::max());
  const double free_log_odds = core::Logit(config_.augmented.free_threshold);
  const std::vector<float>& l = map.log_odds();
  for (std::size_t i = 0; i < l.size(); ++i) {
    if (static_cast<double>(l[i]) <= free_log_odds)
      free_cells_.push_back(static_cast<std::uint32_t>(i));
  }
  ResetAverages();
  trial_.Stop();
  force_update_ = true;
}

void Localizer::SetRecoveryPoses(std::vector<core::Pose2> poses) {
  recovery_poses_ = std::move(poses);
}

void Localizer::Restart(const core::Pose2& X_MR) {
  odometry_since_update_ = core::Pose2::Identity();
  force_update_ = true;
  ResetAverages();
  trial_.Stop();
  lost_ = false;
  reliability_.Reset();
  unweighed_driven_ = 0.0;
  lost_distance_ = 0.0;
  estimate_ = anchor_ = X_MR;
  estimate_stale_ = false;
  challenger_updates_ = 0;
  const std::optional<ClusterMean> c = ClusterAround(particles_, X_MR);
  if (c) estimate_ = c->X_MR;
}

void Localizer::Initialize(const core::Pose2& X_MR, double sigma_xy, double sigma_theta) {
  core::RequireNonNegative("sigma_xy", sigma_xy);
  core::RequireNonNegative("sigma_theta", sigma_theta);
  int n = config_.particles;
  if (config_.kld.enabled) n = std::clamp(n, config_.kld.min_particles, config_.kld.max_particles);
  particles_.assign(static_cast<std::size_t>(n), Particle{});
  const double w = 1.0 / n;
  for (Particle& p : particles_) {
    const double x = X_MR.x + sigma_xy * rng_.Normal();
    const double y = X_MR.y + sigma_xy * rng_.Normal();
    const double theta = X_MR.theta + sigma_theta * rng_.Normal();
    p = {core::Pose2(x, y, theta), w};
  }
  Restart(X_MR);
}

void Localizer::SetParticles(std::vector<Particle> particles) {
  if (particles.empty()) throw core::ConfigError("particles", "must not be empty");
  double total = 0.0;
  for (const Particle& p : particles) {
    if (!std::isfinite(p.X_MR.x) || !std::isfinite(p.X_MR.y) || !std::isfinite(p.X_MR.theta)) {
      throw core::ConfigError("particles", "poses must be finite");
    }
    if (!(p.weight >= 0.0) || !std::isfinite(p.weight)) {
      throw core::ConfigError("particles", "weights must be finite and >= 0");
    }
    total += p.weight;
  }
  if (!(total > 0.0)) throw core::ConfigError("particles", "weights must not all be 0");
  for (Particle& p : particles) p.weight /= total;
  particles_ = std::move(particles);
  Restart(MainCluster(particles_)->X_MR);
}

void Localizer::Predict(const core::OdometryDelta& delta) {
  odometry_since_update_ = core::IntegrateOdometry(odometry_since_update_, delta);
  if (delta.distance == 0.0 && delta.dtheta == 0.0) return;
  const MotionNoise noise = MotionNoiseOf(delta, config_.motion);
  for (Particle& p : particles_) p.X_MR = SampleMotion(p.X_MR, delta, noise, rng_);
  if (trial_.running()) trial_.Predict(delta, noise, rng_);
  anchor_ = core::IntegrateOdometry(anchor_, delta);
  challenger_ = core::IntegrateOdometry(challenger_, delta);
  estimate_stale_ = true;  // the cluster's mean, computed when asked (predictions run at 50 Hz)
}

core::Pose2 Localizer::Estimate() const {
  if (estimate_stale_) {
    const std::optional<ClusterMean> c = ClusterAround(particles_, anchor_);
    estimate_ = c ? c->X_MR : anchor_;
    estimate_stale_ = false;
  }
  return estimate_;
}

std::vector<int> Localizer::SelectBeams(const core::LaserScan& scan) const {
  // Every beam_step-th valid finite reading inside the configured limits.
  const double lo = std::max(scan.range_min, robot_.range_min);
  const double hi = std::min(scan.range_max, robot_.range_max);
  std::vector<int> tested;
  for (std::size_t i = 0; i < scan.size(); i += static_cast<std::size_t>(config_.beam_step)) {
    if (!scan.Valid(i)) continue;
    const double r = scan.ranges[i];
    if (r < lo || r > hi) continue;
    tested.push_back(static_cast<int>(i));
  }
  return tested;
}

std::vector<std::uint8_t> Localizer::TestDynamic(const core::LaserScan& scan,
                                                 const std::vector<int>& tested,
                                                 std::span<const core::Pose2> X_ML,
                                                 LocalizerUpdate* out) const {
  if (!config_.rejection.enabled) return std::vector<std::uint8_t>(tested.size(), 0);
  const std::size_t n = particles_.size();
  std::vector<double> prior(n);
  for (std::size_t j = 0; j < n; ++j) prior[j] = particles_[j].weight;
  double range_sum = 0.0;
  for (const int i : tested) range_sum += scan.ranges[static_cast<std::size_t>(i)];
  out->spread = EndpointSpread(X_ML, prior, range_sum / static_cast<double>(tested.size()));
  std::vector<core::Pose2> sample_X;
  std::vector<double> sample_w;
  StratifiedSample(X_ML, prior, config_.rejection.particles, &sample_X, &sample_w);
  out->rejection_particles = static_cast<int>(sample_X.size());
  DynamicBeamResult result;
  TestDynamicBeams(*beam_model_, *caster_, sample_X, sample_w, scan, tested, config_.rejection.chi,
                   DynamicTestOptions{}, &result);
  return std::move(result.dynamic);
}

WeighedPoints Localizer::KeptEndPoints(const core::LaserScan& scan, const std::vector<int>& tested,
                                    const std::vector<std::uint8_t>& dynamic,
                                    LocalizerUpdate* out) const {
  WeighedPoints points;
  out->beams.assign(scan.size(), BeamUse::kUnused);
  for (std::size_t b = 0; b < tested.size(); ++b) {
    const std::size_t i = static_cast<std::size_t>(tested[b]);
    if (dynamic[b] != 0) {
      if (classes_[b] == BeamClass::kThroughWall) {
        out->beams[i] = BeamUse::kThroughWall;
      } else {
        out->beams[i] = BeamUse::kRejected;
        ++out->beams_rejected;
      }
      continue;
    }
    out->beams[i] = BeamUse::kUsed;
    const double r = scan.ranges[i];
    const double a = scan.Angle(i);
    points.Add(r * std::cos(a), r * std::sin(a));
  }
  out->beams_used = static_cast<int>(points.size());
  return points;
}

WeighedPoints Localizer::ClassifiedEndPoints(const core::LaserScan& scan,
                                          const std::vector<int>& tested,
                                          LocalizerUpdate* out) const {
  const ClassConditionalConfig& cc = config_.class_conditional;
  WeighedPoints points;
  points.mapped_prior = cc.mapped_prior;
  for (std::size_t b = 0; b < tested.size(); ++b) {
    const std::size_t i = static_cast<std::size_t>(tested[b]);
    if (classes_[b] == BeamClass::kUnknown) continue;
    const double r = scan.ranges[i];
    const double a = scan.Angle(i);
    points.Add(r * std::cos(a), r * std::sin(a));
    // A person can only shorten a beam: one that sees through a mapped wall is not unknown.
    const bool may_be_unknown = classes_[b] != BeamClass::kThroughWall;
    points.unknown.push_back(may_be_unknown ? cc.UnknownDensity(r, robot_.range_max) : 0.0);
  }
  const std::vector<double> posterior =
      UnknownPosterior(*field_, Estimate() * robot_.X_RL, points);
  out->beams.assign(scan.size(), BeamUse::kUnused);
  for (std::size_t b = 0, k = 0; b < tested.size(); ++b) {
    if (classes_[b] == BeamClass::kUnknown) continue;
    const bool dynamic = posterior[k++] > cc.unknown_threshold;
    out->beams[static_cast<std::size_t>(tested[b])] = dynamic ? BeamUse::kRejected : BeamUse::kUsed;
    out->beams_rejected += dynamic ? 1 : 0;
  }
  out->beams_used = static_cast<int>(points.size());
  return points;
}

void Localizer::WeighEvidence(const core::LaserScan& scan, const std::vector<int>& tested,
                              double driven, LocalizerUpdate* out) {
  std::vector<double> xs(tested.size()), ys(tested.size());
  for (std::size_t b = 0; b < tested.size(); ++b) {
    const std::size_t i = static_cast<std::size_t>(tested[b]);
    xs[b] = scan.ranges[i] * std::cos(scan.Angle(i));
    ys[b] = scan.ranges[i] * std::sin(scan.Angle(i));
  }
  ClassifyEachBeam(*field_, *caster_, Estimate() * robot_.X_RL, xs, ys, &classes_);
  out->evidence = CountClasses(classes_);
  reliability_.Update(out->evidence, driven);
}

WeighedPoints Localizer::MeasuredPoints(const core::LaserScan& scan, const std::vector<int>& tested,
                                     std::span<const core::Pose2> X_ML, double driven,
                                     LocalizerUpdate* out) {
  if (config_.measurement == MeasurementModel::kClassConditional) {
    WeighEvidence(scan, tested, driven, out);
    return ClassifiedEndPoints(scan, tested, out);
  }
  const std::vector<std::uint8_t> dynamic = TestDynamic(scan, tested, X_ML, out);
  WeighEvidence(scan, tested, driven, out);
  return KeptEndPoints(scan, tested, dynamic, out);
}

void Localizer::UpdateAverages(double w_avg, bool any_beam, double driven,
                               LocalizerUpdate* out) {
  const AugmentedMclConfig& aug = config_.augmented;
  if (any_beam) {
    if (!averages_started_) {
      w_slow_ = w_fast_ = w_avg;
      averages_started_ = true;
    } else {
      w_slow_ += aug.alpha_slow * (w_avg - w_slow_);
      w_fast_ += aug.alpha_fast * (w_avg - w_fast_);
    }
  }
  out->w_avg = w_avg;
  out->w_slow = w_slow_;
  out->w_fast = w_fast_;
  lost_ = averages_started_ && w_fast_ < aug.trigger_ratio * w_slow_;
  lost_distance_ = lost_ ? lost_distance_ + driven : 0.0;
}

bool Localizer::GateOpen() const {
  const core::Pose2& d = odometry_since_update_;
  return force_update_ || std::hypot(d.x, d.y) >= config_.update_distance ||
         std::abs(d.theta) >= core::DegToRad(config_.update_angle_deg);
}

double Localizer::Weigh(std::span<const core::Pose2> X_ML, const WeighedPoints& points,
                        std::vector<double>* w, double* w_avg) {
  // Weighting in log space (eq. 5-6); weights carry over between updates until resampled.
  const std::size_t n = particles_.size();
  std::vector<double> log_w(n);
  w->assign(n, 0.0);
  *w_avg = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double ll = ScanLogLikelihood(*field_, X_ML[j], points);
    log_w[j] = std::log(particles_[j].weight) + ll;
    // The belief's expected likelihood: prior weight times the per-beam geometric mean.
    if (!points.empty()) {
      *w_avg += particles_[j].weight * std::exp(ll / static_cast<double>(points.size()));
    }
  }
  const double evidence = NormalizeLogWeights(log_w, *w);
  for (std::size_t j = 0; j < n; ++j) particles_[j].weight = (*w)[j];
  return evidence;
}

LocalizerUpdate Localizer::Update(const core::LaserScan& scan) {
  LocalizerUpdate out;
  out.particles = static_cast<int>(particles_.size());
  if (field_ == nullptr || particles_.empty()) return out;
  if (!GateOpen()) return out;
  const std::vector<int> tested = SelectBeams(scan);
  // m driven since the reliability was last updated (the gate stays open without a beam).
  const double since = std::hypot(odometry_since_update_.x, odometry_since_update_.y);
  const double driven = since - unweighed_driven_;
  if (tested.empty()) {
    // No beam, no evidence: the reliability decays with the distance; the gate stays open for
    // the next scan.
    reliability_.Update(BeamEvidence{}, driven);
    unweighed_driven_ = since;
    return out;
  }
  unweighed_driven_ = 0.0;
  out.ran = true;
  out.beams_tested = static_cast<int>(tested.size());
  Estimate();  // as of the prediction, before the weights change: recovery draws around it
  force_update_ = false;
  odometry_since_update_ = core::Pose2::Identity();

  const std::size_t n = particles_.size();
  std::vector<core::Pose2> X_ML(n);
  for (std::size_t j = 0; j < n; ++j) X_ML[j] = particles_[j].X_MR * robot_.X_RL;

  // The beams' end points in L as the measurement model weighs them: the paper's dynamic scan
  // point rejection (eq. 7-9) keeps some, the class-conditional model weighs every one.
  const WeighedPoints points = MeasuredPoints(scan, tested, X_ML, driven, &out);

  std::vector<double> w;
  double w_avg = 0.0;
  const double belief_evidence = Weigh(X_ML, points, &w, &w_avg);
  out.n_eff = EffectiveSampleSize(w);

  // Lost while the short-term average likelihood is far below the long-term one; recovery.
  UpdateAverages(w_avg, !points.empty(), since, &out);
  if (config_.augmented.enabled && !points.empty()) RunRecovery(points, belief_evidence, &out);
  if (trial_.running() && out.trial_updates == 0) {  // also while no beam is kept to weigh it
    out.trial_updates = trial_.updates();
    out.trial_log_bayes_factor = trial_.log_bayes_factor();
  }

  // An update that weighed no beam keeps the spread the motion model gave the belief.
  if (!out.reacquired && !points.empty() &&
      out.n_eff < config_.resample_ess_ratio * static_cast<double>(n)) {
    particles_ = config_.kld.enabled ? ResampleKld(w) : ResampleFixed(w);
    const double wn = 1.0 / static_cast<double>(particles_.size());
    for (Particle& p : particles_) p.weight = wn;
    out.resampled = true;
  }
  FollowCluster(out.reacquired);
  out.reliability = reliability_.value();
  out.lost = lost();
  out.particles = static_cast<int>(particles_.size());
  return out;
}

void Localizer::RunRecovery(const WeighedPoints& points, double belief_evidence,
                            LocalizerUpdate* out) {
  const AugmentedMclConfig& aug = config_.augmented;
  if (trial_.running()) {
    trial_.Weigh(*field_, robot_.X_RL, points, belief_evidence, aug.min_beams, rng_);
    out->trial_updates = trial_.updates();
    out->trial_log_bayes_factor = trial_.log_bayes_factor();
    if (lost_ && trial_.updates() >= aug.confirm_updates && TrialWins()) {
      // The trial explains the last scans better than the belief: it becomes the belief.
      particles_ = trial_.Draw(particles_.size(), rng_);
      trial_.Stop();
      w_fast_ = w_slow_;
      lost_ = false;
      out->reacquired = true;
      lost_distance_ = 0.0;
      reliability_.Reset();
    } else if (trial_.weighed() >= aug.max_updates || !lost_) {
      trial_.Stop();
    }
    return;
  }
  if (lost_) trial_.Start(RecoveryHypotheses());
}

bool Localizer::TrialWins() const {
  const AugmentedMclConfig& aug = config_.augmented;
  const std::optional<ClusterMean> main = trial_.Main();
  if (!main || main->weight < aug.min_cluster_share) return false;
  // The farther the trial would move the estimate, the more evidence it needs.
  const double jump = core::Distance(main->X_MR, Estimate());
  return trial_.log_bayes_factor() > aug.margin + aug.jump_cost * jump;
}

void Localizer::FollowCluster(bool jump) {
  const std::optional<ClusterMean> main = MainCluster(particles_);
  const std::optional<ClusterMean> followed = ClusterAround(particles_, anchor_);
  const auto near = [](const core::Pose2& a, const core::Pose2& b) {
    return core::Distance(a, b) <= kClusterRadius &&
           std::abs(core::AngleDiff(a.theta, b.theta)) <= kClusterAngle;
  };
  if (jump || !followed || near(followed->X_MR, main->X_MR) ||
      followed->weight < 0.1 * main->weight) {
    anchor_ = main->X_MR;
    challenger_updates_ = 0;
  } else {
    // Another cluster outweighs the one followed: follow it only once it has stayed the main
    // cluster, at the same place, for confirm_updates updates.
    challenger_updates_ =
        challenger_updates_ > 0 && near(challenger_, main->X_MR) ? challenger_updates_ + 1 : 1;
    challenger_ = main->X_MR;
    if (challenger_updates_ >= config_.augmented.confirm_updates) {
      anchor_ = main->X_MR;
      challenger_updates_ = 0;
    } else {
      anchor_ = followed->X_MR;
    }
  }
  estimate_ = anchor_;
  estimate_stale_ = false;
}

std::vector<Particle> Localizer::ResampleFixed(const std::vector<double>& weights) {
  const std::size_t n = weights.size();
  std::vector<Particle> next(n);
  const std::vector<std::size_t> idx = LowVarianceResample(weights, n, rng_);
  for (std::size_t m = 0; m < n; ++m) next[m] = particles_[idx[m]];
  return next;
}

std::vector<Particle> Localizer::ResampleKld(const std::vector<double>& weights) {
  const KldConfig& kld = config_.kld;
  std::vector<double> cdf(weights.size());
  double c = 0.0;
  for (std::size_t j = 0; j < weights.size(); ++j) cdf[j] = (c += weights[j]);
  const double bin_theta = core::DegToRad(kld.bin_theta_deg);
  std::unordered_set<std::uint64_t> bins;
  std::vector<Particle> next;
  double bound = kld.min_particles;
  while (static_cast<int>(next.size()) < kld.max_particles &&
         (static_cast<double>(next.size()) < bound ||
          static_cast<int>(next.size()) < kld.min_particles)) {
    const double u = rng_.Uniform() * c;
    const std::size_t j = std::min<std::size_t>(
        static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()),
        cdf.size() - 1);
    const core::Pose2& X = particles_[j].X_MR;
    next.push_back(particles_[j]);
    // 21 bits per coordinate (offset to stay non-negative) make one 63-bit key.
    const auto key_of = [](double v) {
      return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v)) + (1 << 20)) &
             0x1fffffULL;
    };
    const std::uint64_t key = key_of(X.x / kld.bin_xy) << 42 | key_of(X.y / kld.bin_xy) << 21 |
                              key_of(X.theta / bin_theta);
    if (bins.insert(key).second) {
      bound = std::max<double>(
          kld.min_particles, KldBound(static_cast<int>(bins.size()), kld.epsilon, kld.z_quantile));
    }
  }
  return next;
}

core::Pose2 Localizer::FreeCellPose() {
  const std::uint32_t cell = free_cells_[rng_.UniformIndex(free_cells_.size())];
  const int w = field_->width();
  const double res = field_->resolution();
  const double x =
      field_->origin().x() +
      (static_cast<double>(cell % static_cast<std::uint32_t>(w)) + rng_.Uniform()) * res;
  const double y =
      field_->origin().y() +
      (static_cast<double>(cell / static_cast<std::uint32_t>(w)) + rng_.Uniform()) * res;
  return {x, y, rng_.Uniform(-core::kPi, core::kPi)};
}

std::vector<core::Pose2> Localizer::RecoveryHypotheses() {
  const AugmentedMclConfig& aug = config_.augmented;
  const int count = aug.hypotheses;
  const int near = static_cast<int>(std::lround(aug.near_fraction * count));
  std::vector<core::Pose2> out;
  out.reserve(static_cast<std::size_t>(count));
  const auto around = [&](const core::Pose2& X, double sigma_xy, double sigma_theta) {
    return core::Pose2(X.x + sigma_xy * rng_.Normal(), X.y + sigma_xy * rng_.Normal(),
                       X.theta + sigma_theta * rng_.Normal());
  };
  // The taught poses within reach of the estimate. The reach widens with the distance driven
  // while lost, by which the belief can have drifted meanwhile. An estimate away from every
  // taught pose (off the route) reaches as far beyond the nearest one: never the whole route,
  // which puts a place that fits a few beams anywhere against a belief that drifted a little.
  const core::Pose2 estimate = Estimate();
  double nearest = std::numeric_limits<double>::infinity();
  for (const core::Pose2& X : recovery_poses_) {
    nearest = std::min(nearest, core::Distance(X, estimate));
  }
  const double reach = std::max(aug.path_reach, nearest) + aug.reach_per_metre * lost_distance_;
  std::vector<std::size_t> reachable;
  for (std::size_t i = 0; i < recovery_poses_.size(); ++i) {
    if (core::Distance(recovery_poses_[i], estimate) <= reach) reachable.push_back(i);
  }
  for (int k = 0; k < count; ++k) {
    if (k < near || (recovery_poses_.empty() && free_cells_.empty())) {
      out.push_back(around(estimate, aug.near_sigma_xy, aug.near_sigma_theta));
    } else if (!recovery_poses_.empty()) {
      core::Pose2 X = recovery_poses_[reachable[rng_.UniformIndex(reachable.size())]];
      // The taught heading is the way the teaching drove; a robot that drives the route the
      // other way (its estimate's heading, which the odometry keeps when the place is lost,
      // says so) is there facing back.
      if (std::cos(core::AngleDiff(estimate.theta, X.theta)) < 0.0) {
        X.theta = core::WrapAngle(X.theta + core::kPi);
      }
      out.push_back(around(X, aug.path_sigma_xy, aug.path_sigma_theta));
    } else {
      out.push_back(FreeCellPose());
    }
  }
  return out;
}

void Localizer::ApplyMapSwitch(const core::OccupancyGrid& next_map, const core::Pose2& X_new_old) {
  for (Particle& p : particles_) p.X_MR = X_new_old * p.X_MR;  // eq. (1)
  estimate_ = X_new_old * Estimate();
  anchor_ = X_new_old * anchor_;
  challenger_ = X_new_old * challenger_;
  SetMap(next_map);
}

}  // namespace retrace::nav
