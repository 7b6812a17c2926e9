#pragma once
// Monte Carlo localization in one partial map (paper §4.2): augmented MCL with the sample
// motion model, the likelihood-field measurement model over a subsampled scan summed in log
// space, motion-gated updates, low-variance resampling when the effective sample size drops,
// recovery trials driven by w_slow / w_fast whose hypotheses lie where a repeating robot can be,
// an estimate that follows one cluster with hysteresis, optional KLD-sampling, and dynamic scan
// point rejection (eq. 7-9) that leaves beams hitting unmapped objects out of the weights (or,
// as an alternative, the class-conditional measurement model: nav/measurement_model.hpp).

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/config.hpp"
#include "core/laser_scan.hpp"
#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "core/twist.hpp"
#include "nav/beam_model.hpp"
#include "nav/grid_ray_caster.hpp"
#include "nav/likelihood_field.hpp"
#include "nav/motion_model.hpp"
#include "nav/particle.hpp"
#include "nav/recovery_trial.hpp"
#include "nav/reliability.hpp"
#include "nav/robot_geometry.hpp"
#include "nav/measurement_model.hpp"

namespace retrace::nav {

/// Dynamic scan point rejection (eq. 7-9).
///
/// The sums of eq. (9) are expectations over the belief. With `particles` > 0 and more particles
/// than that, they run over a stratified sample of that many drawn by prior weight at the
/// quantiles (k + 1/2) / K of the cumulative weights (no random numbers), each distinct particle
/// weighted by how often it was drawn: the ray casts, most of an update's cost, then no longer
/// grow with the particle count. Off by default: on the campus, 100 made the localizer get lost
/// more often, even when used only while the belief was concentrated (docs/HISTORY.md).
struct DynamicRejectionConfig {
  bool enabled = true;
  double chi = 0.9;   ///< a beam is dynamic when its short-reading ratio exceeds chi
  int particles = 0;  ///< particles in the sums of eq. (9): 0 all, else a stratified sample
  BeamModelConfig beam_model;

  template <class V>
  void Reflect(V& v) {
    v("enabled", enabled);
    v("chi", chi);
    v("particles", particles);
    v("beam_model", beam_model);
  }
  /// Throws core::ConfigError naming the key (e.g. "chi", "beam_model.sigma_hit").
  void Validate() const;
};

/// Recovery (augmented MCL's trigger, Probabilistic Robotics Table 8.3, with a teach-and-repeat
/// proposal; docs/METHOD.md, "Recovery"). w_slow and w_fast follow the average measurement
/// likelihood with rates alpha_slow << alpha_fast. The localizer is *lost* while
/// w_fast < trigger_ratio · w_slow: the belief explains the scans much worse than it used to.
/// While lost, and when `enabled`, a recovery trial (nav/recovery_trial.hpp) runs `hypotheses`
/// hypotheses beside the belief: near_fraction of them around the estimate (Gaussian), the rest
/// around the taught poses within reach of the current map (Localizer::SetRecoveryPoses: the map
/// server's route graph gives them; uniformly over the map's free cells when none are given),
/// those within a reach of the estimate: path_reach, widened by reach_per_metre for every metre
/// the odometry has driven since the localizer became lost (how far the belief can have drifted
/// from the truth meanwhile; a robot that stands lost keeps its reach, however many trials fail).
/// The trial replaces the belief only on evidence a wrong place cannot collect, and only while the
/// belief is lost (a trial ends when the belief is found again): it has explained at least
/// confirm_updates scans of at least min_beams kept beams each, weighed on the same beams as the
/// belief and moved by the same odometry; its summed log evidence beats the belief's by margin +
/// jump_cost × the distance it would move the estimate (a prior against far places: a wrong place
/// far away, in a map that distorts distant parts alike, can fit a few scans well); and at least
/// min_cluster_share of its weight agrees on one place. After max_updates it ends. No random
/// particle ever enters the belief directly.
///
/// The average likelihood of an update is the expectation over the belief (prior weights) of
/// the per-beam geometric mean exp(Σ_i log p_i / n) (1/m): with about a hundred beams the plain
/// product would underflow, and the per-beam mean keeps the rates independent of the beam count.
/// Both averages start at the first update's value after Initialize, SetMap or ApplyMapSwitch.
/// With updates every 0.2 m, alpha_slow = 1e-3 remembers about 200 m of route and
/// alpha_fast = 0.1 about 2 m.
struct AugmentedMclConfig {
  bool enabled = true;
  double alpha_slow = 1e-3;
  double alpha_fast = 0.1;
  double trigger_ratio = 0.5;     ///< lost while w_fast < trigger_ratio · w_slow
  int hypotheses = 300;           ///< particles of a recovery trial
  double near_fraction = 0.3;     ///< share of them around the estimate
  double near_sigma_xy = 1.0;     ///< m
  double near_sigma_theta = 0.3;  ///< rad
  double path_sigma_xy = 1.0;     ///< m, around the taught path's poses
  /// rad, around the taught heading, or its reverse where the estimate faces back (a drive that
  /// follows the route backwards)
  double path_sigma_theta = 0.3;
  /// m: only the taught poses this close to the estimate (or as close as the nearest, when farther)
  double path_reach = 10.0;
  double reach_per_metre = 0.1;    ///< m of reach more per metre driven while lost
  int confirm_updates = 5;         ///< scans a trial must explain before it may win
  int min_beams = 6;               ///< kept beams a scan needs to count as explained
  int max_updates = 25;            ///< scans weighed after which a trial that has not won ends
  double margin = 30.0;            ///< nats by which a trial's evidence must beat the belief's
  double min_cluster_share = 0.7;  ///< of the trial's weight in its main cluster, to win
  double jump_cost = 4.0;          ///< nats of evidence more per metre the estimate would move
  double free_threshold = 0.25;    ///< a cell is free when its probability <= this

  template <class V>
  void Reflect(V& v) {
    v("enabled", enabled);
    v("alpha_slow", alpha_slow);
    v("alpha_fast", alpha_fast);
    v("trigger_ratio", trigger_ratio);
    v("hypotheses", hypotheses);
    v("near_fraction", near_fraction);
    v("near_sigma_xy", near_sigma_xy);
    v("near_sigma_theta", near_sigma_theta);
    v("path_sigma_xy", path_sigma_xy);
    v("path_sigma_theta", path_sigma_theta);
    v("path_reach", path_reach);
    v("reach_per_metre", reach_per_metre);
    v("confirm_updates", confirm_updates);
    v("min_beams", min_beams);
    v("max_updates", max_updates);
    v("margin", margin);
    v("min_cluster_share", min_cluster_share);
    v("jump_cost", jump_cost);
    v("free_threshold", free_threshold);
  }
  /// Throws core::ConfigError naming the key.
  void Validate() const;
};

/// KLD-sampling (Fox 2003): when resampling, draw particles until their number exceeds the
/// bound for the number k of occupied bins of a 3-D (x, y, θ) histogram,
/// n = (k - 1) / (2ε) · (1 - 2/(9(k-1)) + sqrt(2/(9(k-1))) z)³, within [min, max]. The draws
/// are then multinomial (binary search on the cumulative weights, O(N log N)).
struct KldConfig {
  bool enabled = false;
  int min_particles = 100;
  int max_particles = 5000;
  double epsilon = 0.05;      ///< bound on the KL divergence
  double z_quantile = 2.326;  ///< upper 1 - δ quantile of the standard normal (δ = 0.01)
  double bin_xy = 0.5;        ///< m
  double bin_theta_deg = 10.0;

  template <class V>
  void Reflect(V& v) {
    v("enabled", enabled);
    v("min_particles", min_particles);
    v("max_particles", max_particles);
    v("epsilon", epsilon);
    v("z_quantile", z_quantile);
    v("bin_xy", bin_xy);
    v("bin_theta_deg", bin_theta_deg);
  }
  /// Throws core::ConfigError naming the key.
  void Validate() const;
};

/// Localizer configuration. Defaults follow the original implementation where sound
/// (docs/METHOD.md): every 10th beam (109 of 1081), z_hit 0.9 / z_short 0.1 / z_max 0.05,
/// λ_short 0.05, χ 0.9, updates after 0.2 m or 2°, resampling when n_eff < 0.5 N; 500 particles
/// instead of 200. The weighting (likelihood_field, z_rand 0.05, σ 0.2 m) and the rejection test
/// (rejection.beam_model, z_rand 0.01, σ 0.1 m) are separate models with separate parameters,
/// as in the paper; see BeamModelConfig for why its z_rand and σ differ.
///
/// Dynamic rejection: the sums of eq. (9) run over the particles weighted by their prior
/// weights (Table 8.5's plain sum right after resampling). Recovery hypotheses never take part:
/// they live in a separate trial until they win (AugmentedMclConfig).
struct LocalizerConfig {
  int particles = 500;              ///< fixed count (the initial count with KLD-sampling)
  int beam_step = 10;               ///< use scan beams 0, step, 2 step, ...
  double update_distance = 0.2;     ///< m of motion before a measurement update
  double update_angle_deg = 2.0;    ///< or this much rotation
  double resample_ess_ratio = 0.5;  ///< resample when n_eff < ratio · N
  /// paper: eq. (7-9) rejection, then eq. (5-6) on the kept beams; class_conditional: every beam
  /// weighed as a mapped or an unknown obstacle (nav/measurement_model.hpp), `rejection` unused
  MeasurementModel measurement = MeasurementModel::kPaper;
  MotionModelConfig motion;
  LikelihoodFieldConfig likelihood_field;
  DynamicRejectionConfig rejection;
  ClassConditionalConfig class_conditional;
  AugmentedMclConfig augmented;
  KldConfig kld;
  ReliabilityConfig reliability;

  template <class V>
  void Reflect(V& v) {
    v("particles", particles);
    v("beam_step", beam_step);
    v("update_distance", update_distance);
    v("update_angle_deg", update_angle_deg);
    v("resample_ess_ratio", resample_ess_ratio);
    v("measurement", measurement);
    v("motion", motion);
    v("likelihood_field", likelihood_field);
    v("rejection", rejection);
    v("class_conditional", class_conditional);
    v("augmented", augmented);
    v("kld", kld);
    v("reliability", reliability);
  }
  /// Throws core::ConfigError naming the key path (e.g. "particles", "rejection.chi").
  void Validate() const;
};

/// How a scan beam was used by an update.
enum class BeamUse : std::uint8_t {
  kUnused,    ///< not selected (beam_step), or not a valid finite reading within the limits
  kUsed,      ///< weighted
  /// classified dynamic: by eq. (9), and left out of the weights (paper); or more likely an
  /// unknown obstacle than a mapped one at the estimate, and weighed as either (class_conditional)
  kRejected,
  /// flagged by eq. (9), but it sees through a mapped wall at the estimate: never dynamic (a
  /// person can only shorten a beam), a contradiction the reliability counts; left out of the
  /// weights as eq. (9) would have left it (the belief's other particles find it short). The
  /// class-conditional model weighs such a beam as mapped only (kUsed).
  kThroughWall,
};

/// Diagnostics of one Update call (no timings: nav has no clock).
struct LocalizerUpdate {
  bool ran = false;        ///< false: gated (no motion since the last update) or no usable beam
  int beams_tested = 0;    ///< selected valid beams
  int beams_used = 0;      ///< beams in the weights
  int beams_rejected = 0;  ///< beams classified dynamic
  /// The belief's spread at the scan's endpoints (m): prior-weighted RMS distance of the particles
  /// from their mean plus the mean tested range times their RMS heading difference (rejection on)
  double spread = 0.0;
  int rejection_particles = 0;  ///< distinct particles in the sums of eq. (9) (rejection on)
  std::vector<BeamUse> beams;   ///< per scan beam (size of the scan when ran, else empty)
  double n_eff = 0.0;           ///< effective sample size after weighting, before resampling
  bool resampled = false;
  double w_avg = 0.0;  ///< average per-beam likelihood of this update (1/m)
  double w_slow = 0.0;
  double w_fast = 0.0;
  /// The tested beams at the estimate (nav/beam_evidence.hpp), the rejected ones included.
  BeamEvidence evidence;
  double reliability = 0.0;  ///< the probability that the estimate is right (nav/reliability.hpp)
  /// after this update: w_fast < trigger_ratio · w_slow, or the reliability below its threshold
  bool lost = false;
  int trial_updates = 0;  ///< scans the running recovery trial has explained (0: none runs)
  double trial_log_bayes_factor = 0.0;  ///< its evidence against the belief's (nats)
  bool reacquired = false;              ///< the trial won: it replaced the belief in this update
  int particles = 0;                    ///< particle count after the update
};

/// Monte Carlo localization with dynamic scan point rejection and teach-and-repeat recovery in a
/// map frame M.
class Localizer {
 public:
  /// Validates the config and the geometry (throws core::ConfigError naming the key); all
  /// randomness comes from rng. Readings outside [robot.range_min, robot.range_max] are
  /// ignored, and robot.range_max is the sensor models' maximum range. No map and no particles
  /// until SetMap and Initialize.
  Localizer(const LocalizerConfig& config, const RobotGeometry& robot, core::Rng rng);
  ~Localizer();
  Localizer(Localizer&&) noexcept;
  Localizer& operator=(Localizer&&) noexcept;

  /// Uses `map` (copied into the likelihood field, distance field and free-cell list) from now
  /// on; the next scan is used even without motion, w_slow / w_fast restart and a running
  /// recovery trial ends.
  void SetMap(const core::OccupancyGrid& map);
  /// Where the robot can be in the current map (M), for recovery hypotheses: the taught poses
  /// within reach through the route graph (nav::RouteGraph::PosesInReach). Empty: uniformly over
  /// the map's free cells.
  void SetRecoveryPoses(std::vector<core::Pose2> poses);
  /// Draws the particles around X_MR (M) with independent Gaussians of std sigma_xy (m) on x
  /// and y and sigma_theta (rad) on the heading. Throws core::ConfigError on a negative or
  /// non-finite sigma. The next scan is used even without motion.
  void Initialize(const core::Pose2& X_MR, double sigma_xy, double sigma_theta);
  /// Replaces the particle set (e.g. a belief carried over from elsewhere); weights are
  /// normalised to sum 1. Throws core::ConfigError for an empty set, a non-finite pose or a
  /// negative or all-zero weight. The next scan is used even without motion.
  void SetParticles(std::vector<Particle> particles);
  /// Moves every particle by one odometry increment (robot frame) with the sample motion
  /// model; call on every odometry tick. Also feeds the motion gate of Update.
  void Predict(const core::OdometryDelta& delta);
  /// Measurement update with a scan in the LiDAR frame L (mounted at robot.X_RL), run
  /// only after update_distance or update_angle_deg of odometry since the last update (or once
  /// after Initialize, SetMap, ApplyMapSwitch): standing still never reuses a scan.
  LocalizerUpdate Update(const core::LaserScan& scan);

  /// The robot pose X_MR in M: the weighted mean (circular mean for θ) of the cluster the
  /// estimate follows (nav/cluster_estimate.hpp), moved with every prediction. After each update
  /// it moves to the belief's main cluster, unless that lies elsewhere (beyond kClusterRadius or
  /// kClusterAngle) while the followed cluster still holds a tenth of its weight: then only
  /// after the main cluster has stayed there for augmented.confirm_updates updates. A single
  /// update therefore cannot carry the estimate far. The identity before Initialize.
  core::Pose2 Estimate() const;
  /// Paper eq. (1) at a map switch: every particle becomes X_new_old * X_old_R (so does the
  /// estimate), then next_map replaces the map as in SetMap.
  /// X_new_old is the old map frame in the new one, i.e. inverse(X_{M_k S}) (docs/DESIGN.md §2).
  void ApplyMapSwitch(const core::OccupancyGrid& next_map, const core::Pose2& X_new_old);

  const std::vector<Particle>& particles() const { return particles_; }
  const LocalizerConfig& config() const { return config_; }
  const RobotGeometry& robot() const { return robot_; }
  /// The current map's likelihood field (requires a map: SetMap).
  const LikelihoodField& likelihood_field() const;
  /// As of the last update: the belief explains the scans much worse than it used to, or the
  /// scans no longer support the estimate (its reliability fell below the threshold).
  bool lost() const { return lost_ || reliability_.unreliable(); }
  /// As of the last update: the belief explains the scans much worse than it used to (augmented
  /// MCL's trigger, which starts a recovery trial).
  bool misfit() const { return lost_; }
  /// The probability that the estimate is right, as of the last update.
  double reliability() const { return reliability_.value(); }

 private:
  void ResetAverages();
  std::vector<int> SelectBeams(const core::LaserScan& scan) const;
  // Per tested beam, 1 where eq. (9) finds it dynamic; fills out's spread and particle count.
  std::vector<std::uint8_t> TestDynamic(const core::LaserScan& scan, const std::vector<int>& tested,
                                        std::span<const core::Pose2> X_ML,
                                        LocalizerUpdate* out) const;
  // The tested beams' classes at the estimate (into classes_) and the reliability.
  void WeighEvidence(const core::LaserScan& scan, const std::vector<int>& tested, double driven,
                     LocalizerUpdate* out);
  // update_distance or update_angle_deg of odometry since the last update, or forced.
  bool GateOpen() const;
  // Weighs the particles (LiDAR poses X_ML) on the points: their normalised weights into w, the
  // belief's average per-beam likelihood into w_avg; returns the log of the belief's evidence
  // for the scan.
  double Weigh(std::span<const core::Pose2> X_ML, const WeighedPoints& points,
               std::vector<double>* w, double* w_avg);
  // w_slow, w_fast and the lost state after an update whose average likelihood is w_avg, and
  // the distance driven while lost (`driven` since the last update).
  void UpdateAverages(double w_avg, bool any_beam, double driven, LocalizerUpdate* out);
  std::vector<Particle> ResampleFixed(const std::vector<double>& weights);
  std::vector<Particle> ResampleKld(const std::vector<double>& weights);
  std::vector<core::Pose2> RecoveryHypotheses();
  core::Pose2 FreeCellPose();
  // The paper's model: the end points (L) of the tested beams the rejection kept; marks every
  // beam's use in `out` (a flagged beam that sees through a mapped wall, by classes_, is not
  // dynamic).
  WeighedPoints KeptEndPoints(const core::LaserScan& scan, const std::vector<int>& tested,
                           const std::vector<std::uint8_t>& dynamic, LocalizerUpdate* out) const;
  // The class-conditional model: every tested beam's end point (L) with its unknown-class
  // density (0 where it sees through a mapped wall, by classes_); marks as dynamic the beams
  // more likely unknown than mapped at the estimate.
  WeighedPoints ClassifiedEndPoints(const core::LaserScan& scan, const std::vector<int>& tested,
                                 LocalizerUpdate* out) const;
  // The tested beams' end points as the measurement model weighs them, with the beams' uses and
  // evidence in `out` (`driven`: m since the reliability was last updated).
  WeighedPoints MeasuredPoints(const core::LaserScan& scan, const std::vector<int>& tested,
                            std::span<const core::Pose2> X_ML, double driven, LocalizerUpdate* out);
  void RunRecovery(const WeighedPoints& points, double belief_evidence, LocalizerUpdate* out);
  // The running trial has the evidence to replace the belief (AugmentedMclConfig).
  bool TrialWins() const;
  void FollowCluster(bool jump);
  void Restart(const core::Pose2& X_MR);

  LocalizerConfig config_;
  RobotGeometry robot_;
  core::Rng rng_;
  std::unique_ptr<LikelihoodField> field_;
  std::unique_ptr<GridRayCaster> caster_;
  std::unique_ptr<BeamModel> beam_model_;
  std::vector<std::uint32_t> free_cells_;  // row-major indices of free cells
  std::vector<core::Pose2> recovery_poses_;
  std::vector<Particle> particles_;
  RecoveryTrial trial_;
  core::Pose2 odometry_since_update_;
  bool force_update_ = false;
  bool averages_started_ = false;
  double w_slow_ = 0.0;
  double w_fast_ = 0.0;
  bool lost_ = false;
  Reliability reliability_;
  double unweighed_driven_ = 0.0;  // m of odometry already counted by the reliability
  std::vector<BeamClass> classes_;  // scratch: the tested beams' classes
  // The estimate and the cluster it follows (moved by every prediction); a main cluster seen
  // elsewhere, and for how many updates in a row.
  mutable core::Pose2 estimate_;
  mutable bool estimate_stale_ = false;
  core::Pose2 anchor_;
  core::Pose2 challenger_;
  int challenger_updates_ = 0;
  double lost_distance_ = 0.0;  // m the odometry drove since the localizer became lost
};

}  // namespace retrace::nav
