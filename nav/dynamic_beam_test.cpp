#include "nav/dynamic_beam_test.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.hpp"

namespace retrace::nav {
namespace {

// For each tested beam b (index beams[b] into the scan, checked valid): its reading z[b] (m),
// the short decay of that reading, and its unit direction (ux[b], uy[b]) in L.
void ReadTestedBeams(const BeamModel& model, const core::LaserScan& scan,
                     std::span<const int> beams, std::span<double> z, std::span<double> decay,
                     std::span<double> ux, std::span<double> uy) {
  for (std::size_t b = 0; b < beams.size(); ++b) {
    const int i = beams[b];
    RETRACE_CHECK(i >= 0 && static_cast<std::size_t>(i) < scan.size() &&
                  scan.Valid(static_cast<std::size_t>(i)));
    z[b] = scan.ranges[static_cast<std::size_t>(i)];
    decay[b] = model.ShortDecay(z[b]);
    const double a = scan.Angle(static_cast<std::size_t>(i));
    ux[b] = std::cos(a);
    uy[b] = std::sin(a);
  }
}

// The particles that take part in the dynamic-point test (zero weights add nothing to either
// sum), in the order of their headings: consecutive rays of a beam then point in nearly the same
// direction, and CastMany clears their common start once per bundle. The sums stay in particle
// order: order[k] is the place in it of the k-th particle by heading.
struct DynamicTestParticles {
  std::vector<std::size_t> order;
  std::vector<double> px, py, c, s;  // position (M) and rotation (cos, sin of the heading)
  std::vector<double> w_used;        // the weights in particle order; empty for equal weights
};

DynamicTestParticles SortedTestParticles(std::span<const core::Pose2> X_ML,
                                         std::span<const double> weights) {
  const std::size_t np = X_ML.size();
  std::vector<double> pc(np), ps(np), pw(np);
  std::vector<std::size_t> used;
  used.reserve(np);
  for (std::size_t j = 0; j < np; ++j) {
    pc[j] = std::cos(X_ML[j].theta);  // one rotation per particle
    ps[j] = std::sin(X_ML[j].theta);
    pw[j] = weights.empty() ? 1.0 : weights[j];
    if (pw[j] > 0.0) used.push_back(j);
  }
  const std::size_t nu = used.size();
  DynamicTestParticles p;
  if (!weights.empty()) {
    for (const std::size_t j : used) p.w_used.push_back(pw[j]);
  }
  // (A NaN heading sorts last: it must not break the ordering std::sort relies on.)
  p.order.resize(nu);
  std::vector<double> heading(nu);
  for (std::size_t u = 0; u < nu; ++u) {
    p.order[u] = u;
    const double theta = X_ML[used[u]].theta;
    heading[u] = std::isnan(theta) ? std::numeric_limits<double>::infinity() : theta;
  }
  std::sort(p.order.begin(), p.order.end(), [&](std::size_t a, std::size_t b) {
    return heading[a] < heading[b] || (heading[a] == heading[b] && a < b);
  });
  p.px.resize(nu);
  p.py.resize(nu);
  p.c.resize(nu);
  p.s.resize(nu);
  for (std::size_t k = 0; k < nu; ++k) {
    const std::size_t j = used[p.order[k]];
    p.px[k] = X_ML[j].x;
    p.py[k] = X_ML[j].y;
    p.c[k] = pc[j];
    p.s[k] = ps[j];
  }
  return p;
}

// The particles of the sample that decides most beams: this many, spread over the heading order.
constexpr std::size_t kSampleSize = 32;
// A bounded ratio must clear χ by this much to decide a beam: far above the rounding of the
// sums (a relative 1e-13 for a thousand terms), so the exact sums would decide it the same way.
constexpr double kDecisionMargin = 1e-9;
// The second stage casts every ray to this many σ_hit beyond the reading: a z* farther out adds
// at most exp(-18) of p_hit's peak, less than the rounding of p_rand's share.
constexpr double kClearSigmas = 6.0;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Some of the test's particles (positions in heading order), gathered for casting, with the
// rays of the current beam and their ranges.
struct RayGroup {
  std::vector<std::size_t> at;       // positions in heading order
  std::vector<double> px, py, c, s;  // gathered from DynamicTestParticles
  std::vector<double> w;             // their weights (1 for equal weights)
  double weight_sum = 0.0;
  std::vector<double> rx, ry, z;  // per beam: ray directions (M) and cast ranges (m)

  void Clear() {
    at.clear();
    px.clear();
    py.clear();
    c.clear();
    s.clear();
    w.clear();
    weight_sum = 0.0;
  }
  void Add(const DynamicTestParticles& p, std::size_t k) {
    at.push_back(k);
    px.push_back(p.px[k]);
    py.push_back(p.py[k]);
    c.push_back(p.c[k]);
    s.push_back(p.s[k]);
    w.push_back(p.w_used.empty() ? 1.0 : p.w_used[p.order[k]]);
    weight_sum += w.back();
  }
  // Casts the group's rays along the beam direction (ux, uy) in L up to max_range (m).
  void Cast(const GridRayCaster& caster, RayCastMethod method, double ux, double uy,
            double max_range) {
    const std::size_t n = at.size();
    rx.resize(n);
    ry.resize(n);
    z.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      rx[k] = c[k] * ux - s[k] * uy;
      ry[k] = s[k] * ux + c[k] * uy;
    }
    if (method == RayCastMethod::kSphereTracing) {
      caster.CastMany(px, py, rx, ry, max_range, z);
    } else {
      for (std::size_t k = 0; k < n; ++k)
        z[k] = caster.CastDda(px[k], py[k], rx[k], ry[k], max_range);
    }
  }
};

// Bounds on eq. (9)'s two weighted sums over a beam's particles: the short parts and the rest of
// p_beam. The ratio short / (short + rest) rises with the first and falls with the second.
struct SumBounds {
  double short_lo = 0.0, short_hi = 0.0, rest_lo = 0.0, rest_hi = 0.0;

  void AddExact(double w, const BeamModel::Terms& t) {
    const double rest = t.total - t.short_part;
    short_lo += w * t.short_part;
    short_hi += w * t.short_part;
    rest_lo += w * rest;
    rest_hi += w * rest;
  }
  void Add(double w, const BeamModel::TermBounds& b) {
    short_lo += w * b.short_lo;
    short_hi += w * b.short_hi;
    rest_lo += w * b.rest_lo;
    rest_hi += w * b.rest_hi;
  }
  // 1: the ratio certainly exceeds chi; 0: it certainly does not; -1: the bounds do not tell.
  // (NaN from infinite or empty bounds compares false: undecided.)
  int Decide(double chi) const {
    if (short_hi / (short_hi + rest_lo) < chi - kDecisionMargin) return 0;
    if (short_lo / (short_lo + rest_hi) > chi + kDecisionMargin) return 1;
    return -1;
  }
};

// The test of one call: its particles split into the sample and the rest, and the beams run
// through the stages.
class BeamTester {
 public:
  BeamTester(const BeamModel& model, const GridRayCaster& caster, const DynamicTestParticles& p,
             const DynamicTestOptions& options)
      : model_(model), caster_(caster), p_(p), options_(options), z_star_(p.order.size()) {
    const std::size_t nu = p.order.size();
    if (!options.decide_by_bounds) {
      for (std::size_t k = 0; k < nu; ++k) rest_.Add(p, k);
      return;
    }
    // Every (nu / kSampleSize)-th particle by heading: the sample sees the belief's whole spread.
    std::vector<std::uint8_t> in_sample(nu, 0);
    if (nu > 2 * kSampleSize) {
      for (std::size_t m = 0; m < kSampleSize; ++m)
        in_sample[(2 * m + 1) * nu / (2 * kSampleSize)] = 1;
    }
    for (std::size_t k = 0; k < nu; ++k) (in_sample[k] != 0 ? sample_ : rest_).Add(p, k);
  }

  // Whether the beam with reading z (m), short decay and direction (ux, uy) in L is dynamic;
  // *ratio its ratio, or NaN when bounds decided it.
  bool Test(double z, double decay, double ux, double uy, double chi, double* ratio);

 private:
  // The bounds of the sums from group g's cast ranges; a range beyond `limited` (m) from a cast
  // that stopped there is only known to be farther.
  void AddGroup(const RayGroup& g, double z, double decay, double limited, SumBounds* b) const;
  // The exact ratio of eq. (9) once the sample and the rest are cast to `limited` (m): casts
  // the rays that stopped there on to range_max and sums all terms in particle order.
  double ExactRatio(double z, double decay, double ux, double uy, double limited);

  const BeamModel& model_;
  const GridRayCaster& caster_;
  const DynamicTestParticles& p_;
  DynamicTestOptions options_;
  RayGroup sample_, rest_, far_;
  std::vector<double> z_star_;  // in particle order
  BeamModel::Scratch scratch_;
};

void BeamTester::AddGroup(const RayGroup& g, double z, double decay, double limited,
                          SumBounds* b) const {
  const BeamModel::TermBounds beyond = model_.BoundsBeyond(z, decay, limited);
  for (std::size_t k = 0; k < g.at.size(); ++k) {
    if (g.z[k] == kNoHit && limited < model_.range_max()) {
      b->Add(g.w[k], beyond);
    } else {
      b->AddExact(g.w[k], model_.EvaluateFast(z, decay, g.z[k]));
    }
  }
}

bool BeamTester::Test(double z, double decay, double ux, double uy, double chi, double* ratio) {
  const double range_max = model_.range_max();
  if (!options_.decide_by_bounds) {
    rest_.Cast(caster_, options_.method, ux, uy, range_max);
    *ratio = ExactRatio(z, decay, ux, uy, range_max);
    return *ratio > chi;
  }
  // Stage 1: the sample cast to a little beyond the reading, the rest unknown. Decides most beams
  // that agree with the map: a few particles' p_hit outweighs any short part the rest can add.
  const double limited = std::min(z + kClearSigmas * model_.config().sigma_hit, range_max);
  SumBounds sample_bounds;
  if (!sample_.at.empty()) {
    sample_.Cast(caster_, options_.method, ux, uy, limited);
    AddGroup(sample_, z, decay, limited, &sample_bounds);
    SumBounds b = sample_bounds;
    b.Add(rest_.weight_sum, model_.BoundsBeyond(z, decay, -1.0));
    if (const int d = b.Decide(chi); d >= 0) {
      *ratio = kNaN;
      return d == 1;
    }
  }
  // Stage 2: every ray cast to a little beyond the reading. Decides the beams that end short of
  // the map: most rays are clear past the reading, which bounds their terms tightly.
  rest_.Cast(caster_, options_.method, ux, uy, limited);
  SumBounds b = sample_bounds;
  AddGroup(rest_, z, decay, limited, &b);
  if (const int d = b.Decide(chi); d >= 0) {
    *ratio = kNaN;
    return d == 1;
  }
  *ratio = ExactRatio(z, decay, ux, uy, limited);
  return *ratio > chi;
}

double BeamTester::ExactRatio(double z, double decay, double ux, double uy, double limited) {
  const double range_max = model_.range_max();
  // The rays that stopped at `limited` go on to range_max; the others' ranges are exact.
  far_.Clear();
  for (const RayGroup* g : {&sample_, &rest_}) {
    for (std::size_t k = 0; k < g->at.size(); ++k) {
      const std::size_t i = p_.order[g->at[k]];
      z_star_[i] = g->z[k];
      if (g->z[k] == kNoHit && limited < range_max) far_.Add(p_, g->at[k]);
    }
  }
  if (!far_.at.empty()) {
    far_.Cast(caster_, options_.method, ux, uy, range_max);
    for (std::size_t k = 0; k < far_.at.size(); ++k) z_star_[p_.order[far_.at[k]]] = far_.z[k];
  }
  const BeamModel::Terms sums = model_.SumTerms(z, decay, z_star_, p_.w_used, &scratch_);
  return sums.total > 0.0 ? sums.short_part / sums.total : 0.0;  // eq. (9)
}

}  // namespace

void TestDynamicBeams(const BeamModel& model, const GridRayCaster& caster,
                      std::span<const core::Pose2> X_ML, std::span<const double> weights,
                      const core::LaserScan& scan, std::span<const int> beams, double chi,
                      const DynamicTestOptions& options, DynamicBeamResult* result) {
  RETRACE_CHECK(result != nullptr);
  RETRACE_CHECK(weights.empty() || weights.size() == X_ML.size());
  const std::size_t nb = beams.size();
  result->dynamic.assign(nb, 0);
  result->ratio.assign(nb, 0.0);
  if (nb == 0 || X_ML.empty()) return;
  std::vector<double> z(nb), decay(nb), ux(nb), uy(nb);
  ReadTestedBeams(model, scan, beams, z, decay, ux, uy);
  const DynamicTestParticles p = SortedTestParticles(X_ML, weights);
  if (p.order.empty()) return;
  BeamTester tester(model, caster, p, options);
  // Beam-major order: the particles' rays of one beam run side by side over the same cells,
  // so consecutive casts hit the cache.
  for (std::size_t b = 0; b < nb; ++b) {
    result->dynamic[b] = tester.Test(z[b], decay[b], ux[b], uy[b], chi, &result->ratio[b]) ? 1 : 0;
  }
}

}  // namespace retrace::nav
