#include "bench/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <optional>
#include <utility>

#include "bench/local_truth.hpp"
#include "core/angle.hpp"
#include "core/check.hpp"
#include "io/csv_writer.hpp"

namespace retrace::bench {

void MetricsConfig::Validate() const {
  core::RequirePositive("station_spacing", station_spacing);
  core::RequirePositive("lost_error", lost_error);
  core::RequireNonNegative("collision_merge_time", collision_merge_time);
  core::RequireNonNegative("collision_driving_speed", collision_driving_speed);
  core::RequirePositive("collision_speed_window", collision_speed_window);
  core::RequirePositive("match_window", match_window);
  core::RequirePositive("match_fallback_distance", match_fallback_distance);
}

namespace {

using core::Pose2;
using core::Vec2;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
// A progress step bigger than this between consecutive samples is a jump of the match (a
// fallback to another part of the path), not a crossing of the stations in between (m).
constexpr double kMaxCrossingStep = 2.0;
// Consecutive taught positions closer than this are one vertex (m): a standing robot would
// otherwise give zero-length segments without a direction.
constexpr double kDuplicateDistance = 1e-9;

double SegmentDistance2(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  double t = len2 > 0.0 ? (p - a).dot(d) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return (p - (a + t * d)).squaredNorm();
}

// A uniform grid over items (segments, or points as zero-length segments) for exact nearest
// queries: rings of cells around the query are searched until no unvisited cell can hold a
// nearer item.
class NearestGrid {
 public:
  NearestGrid() = default;
  NearestGrid(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    RETRACE_CHECK(a.size() == b.size());
    if (a.empty()) return;
    Vec2 lo = a[0], hi = a[0];
    for (std::size_t i = 0; i < a.size(); ++i) {
      lo = lo.cwiseMin(a[i]).cwiseMin(b[i]);
      hi = hi.cwiseMax(a[i]).cwiseMax(b[i]);
    }
    const Vec2 extent = hi - lo;
    // At most 1024 cells a side; 1 m cells hold a few dozen samples of a taught path.
    cell_ = std::max(1.0, std::max(extent.x(), extent.y()) / 1024.0);
    origin_ = lo;
    nx_ = static_cast<long long>(extent.x() / cell_) + 1;
    ny_ = static_cast<long long>(extent.y() / cell_) + 1;
    // Each item goes into every cell of its bounding box that it passes through.
    std::vector<std::pair<std::size_t, std::size_t>> entries;  // (cell, item)
    entries.reserve(a.size() * 2);
    const double half_diagonal = 0.5 * std::sqrt(2.0) * cell_ * (1.0 + 1e-9);
    for (std::size_t i = 0; i < a.size(); ++i) {
      const long long x0 = CellX(std::min(a[i].x(), b[i].x()));
      const long long x1 = CellX(std::max(a[i].x(), b[i].x()));
      const long long y0 = CellY(std::min(a[i].y(), b[i].y()));
      const long long y1 = CellY(std::max(a[i].y(), b[i].y()));
      const bool single = x0 == x1 && y0 == y1;
      for (long long y = y0; y <= y1; ++y) {
        for (long long x = x0; x <= x1; ++x) {
          const Vec2 centre = origin_ + Vec2((static_cast<double>(x) + 0.5) * cell_,
                                             (static_cast<double>(y) + 0.5) * cell_);
          if (single || SegmentDistance2(centre, a[i], b[i]) <= half_diagonal * half_diagonal) {
            entries.emplace_back(static_cast<std::size_t>(y * nx_ + x), i);
          }
        }
      }
    }
    std::stable_sort(entries.begin(), entries.end(),
                     [](const auto& l, const auto& r) { return l.first < r.first; });
    start_.assign(static_cast<std::size_t>(nx_ * ny_) + 1, 0);
    for (const auto& [c, i] : entries) ++start_[c + 1];
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    items_.reserve(entries.size());
    for (const auto& [c, i] : entries) items_.push_back(i);
  }

  bool empty() const { return items_.empty(); }

  // The item with the smallest dist2(item) (lowest index on ties), kNone when empty.
  template <class Dist2>
  std::size_t Nearest(const Vec2& p, Dist2 dist2) const {
    if (items_.empty() || !p.allFinite()) return kNone;
    const long long cx = CellX(p.x());
    const long long cy = CellY(p.y());
    // Rings closer than the grid's edge hold nothing: start at the first one that touches it.
    const long long out_x = cx < 0 ? -cx : (cx >= nx_ ? cx - nx_ + 1 : 0);
    const long long out_y = cy < 0 ? -cy : (cy >= ny_ ? cy - ny_ + 1 : 0);
    const long long r_first = std::max(out_x, out_y);
    const long long r_last = std::max({cx, nx_ - 1 - cx, cy, ny_ - 1 - cy});
    double best_d2 = kInf;
    std::size_t best = kNone;
    auto visit = [&](long long x, long long y) {
      if (x < 0 || x >= nx_ || y < 0 || y >= ny_) return;
      const std::size_t c = static_cast<std::size_t>(y * nx_ + x);
      for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) {
        const std::size_t i = items_[k];
        const double d2 = dist2(i);
        if (d2 < best_d2 || (d2 == best_d2 && i < best)) {
          best_d2 = d2;
          best = i;
        }
      }
    };
    for (long long r = r_first; r <= r_last; ++r) {
      if (r == 0) {
        visit(cx, cy);
      } else {
        for (long long x = std::max(cx - r, 0LL); x <= std::min(cx + r, nx_ - 1); ++x) {
          visit(x, cy - r);
          visit(x, cy + r);
        }
        for (long long y = std::max(cy - r + 1, 0LL); y <= std::min(cy + r - 1, ny_ - 1); ++y) {
          visit(cx - r, y);
          visit(cx + r, y);
        }
      }
      // Every cell of ring r + 1 is at least r cells away from p.
      const double reach = static_cast<double>(r) * cell_;
      if (best != kNone && best_d2 <= reach * reach) break;
    }
    return best;
  }

 private:
  long long CellX(double x) const { return ToCell((x - origin_.x()) / cell_); }
  long long CellY(double y) const { return ToCell((y - origin_.y()) / cell_); }
  static long long ToCell(double v) {
    return static_cast<long long>(std::floor(std::clamp(v, -1e12, 1e12)));
  }

  Vec2 origin_{0.0, 0.0};
  double cell_ = 1.0;
  long long nx_ = 0;
  long long ny_ = 0;
  std::vector<std::size_t> start_;  // items of cell c: items_[start_[c], start_[c + 1])
  std::vector<std::size_t> items_;
};

std::vector<double> CumulativeArc(const std::vector<Vec2>& points) {
  std::vector<double> arc(points.size(), 0.0);
  for (std::size_t i = 1; i < points.size(); ++i) {
    arc[i] = arc[i - 1] + (points[i] - points[i - 1]).norm();
  }
  return arc;
}

struct Projection {
  double distance = kInf;  // m, to the closest point of the path
  double s = 0.0;          // m, arc length of the foot point (beyond the ends: extended)
  double lateral = 0.0;    // m, signed offset, > 0 left of the path direction
};

// The taught path: the polyline through the teaching drive's ground-truth positions.
class TaughtPath {
 public:
  explicit TaughtPath(const std::vector<Pose2>& X_WR) {
    for (const Pose2& X : X_WR) {
      const Vec2 p = X.translation();
      if (points_.empty() || (p - points_.back()).norm() > kDuplicateDistance) {
        points_.push_back(p);
      }
    }
    arc_ = CumulativeArc(points_);
    std::vector<Vec2> a, b;
    for (std::size_t i = 0; i < segments(); ++i) {
      a.push_back(points_[i]);
      b.push_back(points_[End(i)]);
    }
    grid_ = NearestGrid(a, b);
  }

  bool empty() const { return points_.empty(); }
  double length() const { return arc_.empty() ? 0.0 : arc_.back(); }

  // Exact distance from p to the path (m); NaN for an empty path.
  double Distance(const Vec2& p) const {
    const std::size_t i = grid_.Nearest(p, [&](std::size_t k) { return Dist2(k, p); });
    return i == kNone ? kMetricNaN : std::sqrt(Dist2(i, p));
  }

  Projection ProjectGlobal(const Vec2& p) const {
    const std::size_t i = grid_.Nearest(p, [&](std::size_t k) { return Dist2(k, p); });
    return i == kNone ? Projection{} : Finish(i, p);
  }

  // Projection onto the segments that overlap [s_lo, s_hi] of arc length.
  Projection ProjectWindow(const Vec2& p, double s_lo, double s_hi) const {
    if (empty()) return {};
    const auto it = std::upper_bound(arc_.begin(), arc_.end(), s_lo);
    std::size_t i = it == arc_.begin() ? 0 : static_cast<std::size_t>(it - arc_.begin()) - 1;
    i = std::min(i, segments() - 1);
    std::size_t best = i;
    double best_d2 = kInf;
    for (; i < segments() && arc_[i] <= s_hi; ++i) {
      const double d2 = Dist2(i, p);
      if (d2 < best_d2) {
        best_d2 = d2;
        best = i;
      }
    }
    return Finish(best, p);
  }

 private:
  // Segment i runs from point i to point i + 1; a one-point path has one zero-length segment.
  std::size_t segments() const { return points_.size() <= 1 ? points_.size() : points_.size() - 1; }
  std::size_t End(std::size_t i) const { return std::min(i + 1, points_.size() - 1); }
  double Dist2(std::size_t i, const Vec2& p) const {
    return SegmentDistance2(p, points_[i], points_[End(i)]);
  }

  Projection Finish(std::size_t i, const Vec2& p) const {
    const Vec2& a = points_[i];
    const Vec2 d = points_[End(i)] - a;
    const double len = d.norm();
    Projection out;
    out.distance = std::sqrt(Dist2(i, p));
    if (len == 0.0) {
      out.s = arc_[i];
      return out;
    }
    const Vec2 u = d / len;
    const Vec2 ap = p - a;
    const double t_raw = ap.dot(u);  // m along the segment
    const double cross = u.x() * ap.y() - u.y() * ap.x();
    const bool before_start = i == 0 && t_raw < 0.0;
    const bool after_end = i + 1 == segments() && t_raw > len;
    if (before_start || after_end || (t_raw >= 0.0 && t_raw <= len)) {
      // On the segment, or on the extension of the first / last one.
      out.s = arc_[i] + t_raw;
      out.lateral = cross;
    } else {
      // Closest to an inner vertex (outside of a corner): the side from the segment chosen.
      out.s = arc_[i] + std::clamp(t_raw, 0.0, len);
      out.lateral = std::copysign(out.distance, cross);
    }
    return out;
  }

  std::vector<Vec2> points_;
  std::vector<double> arc_;
  NearestGrid grid_;
};

// Monotone progress along the taught path: windowed around the previous match, global only
// when the window's best is far.
class PathTracker {
 public:
  PathTracker(const TaughtPath& path, const MetricsConfig& config) : path_(path), config_(config) {}

  Projection Track(const Vec2& p) {
    const double centre = std::clamp(s_prev_, 0.0, path_.length());
    Projection best =
        path_.ProjectWindow(p, centre - config_.match_window, centre + config_.match_window);
    if (best.distance > config_.match_fallback_distance) {
      const Projection global = path_.ProjectGlobal(p);
      if (global.distance < best.distance) best = global;
    }
    s_prev_ = best.s;
    return best;
  }

 private:
  const TaughtPath& path_;
  const MetricsConfig& config_;
  double s_prev_ = 0.0;
};

// What one run's metrics need from the teach trace, built once per run.
struct TeachIndex {
  TeachIndex(const TeachTrace& teach, const MetricsConfig& config) : path(teach.X_WR) {
    matchers.reserve(teach.maps.size());
    for (const TeachMapTrace& map : teach.maps) {
      if (map.X_WR.empty() || map.X_WR.size() != map.X_MR.size()) {
        matchers.emplace_back();  // no reference: its samples are left out
      } else {
        matchers.emplace_back(std::in_place, map, config.match_window,
                              config.match_fallback_distance);
      }
    }
  }
  LocalTruth* Matcher(int k) {
    if (k < 0 || static_cast<std::size_t>(k) >= matchers.size()) return nullptr;
    std::optional<LocalTruth>& m = matchers[static_cast<std::size_t>(k)];
    return m ? &*m : nullptr;
  }
  TaughtPath path;
  std::vector<std::optional<LocalTruth>> matchers;
};

RunSeries Series(TeachIndex& index, const RunTrace& run, const MetricsConfig& config,
                 bool with_localization) {
  const std::size_t n = run.samples.size();
  RunSeries out;
  out.tracking_error_m.assign(n, kMetricNaN);
  out.progress_m.assign(n, kMetricNaN);
  out.lateral_offset_m.assign(n, kMetricNaN);
  if (with_localization) {
    out.localization_error_m.assign(n, kMetricNaN);
    out.localization_error_rad.assign(n, kMetricNaN);
  }
  PathTracker tracker(index.path, config);
  int current_map = std::numeric_limits<int>::min();
  for (std::size_t i = 0; i < n; ++i) {
    const PlaybackSample& sample = run.samples[i];
    const Vec2 p = sample.X_WR.translation();
    if (!index.path.empty()) {
      if (with_localization) out.tracking_error_m[i] = index.path.Distance(p);
      const Projection proj = tracker.Track(p);
      out.progress_m[i] = proj.s;
      out.lateral_offset_m[i] = proj.lateral;
    }
    if (!with_localization) continue;
    LocalTruth* matcher = index.Matcher(sample.map_index);
    if (sample.map_index != current_map) {
      current_map = sample.map_index;
      if (matcher != nullptr) matcher->Reset();
    }
    if (matcher == nullptr) continue;
    const PoseError e = Compare(sample.X_MR, matcher->InMap(sample.X_WR));
    out.localization_error_m[i] = e.distance;
    out.localization_error_rad[i] = e.angle;
  }
  return out;
}

double FractionAbove(const std::vector<double>& values, double threshold) {
  int n = 0, above = 0;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    ++n;
    if (v > threshold) ++above;
  }
  return n > 0 ? static_cast<double>(above) / n : kMetricNaN;
}

double Ratio(std::int64_t num, std::int64_t den) {
  return den > 0 ? static_cast<double>(num) / static_cast<double>(den) : kMetricNaN;
}

void FinishDynamicPoints(DynamicPointStats& d) {
  d.rejected_fraction = Ratio(d.beams_rejected, d.beams_tested);
  d.precision = Ratio(d.true_positive, d.true_positive + d.false_positive);
  d.recall = Ratio(d.true_positive, d.true_positive + d.false_negative);
}

// min that skips NaN (a NaN `a` is "no value yet").
double MinSkipNaN(double a, double b) {
  if (std::isnan(b)) return a;
  if (std::isnan(a)) return b;
  return std::min(a, b);
}
double MaxSkipNaN(double a, double b) {
  if (std::isnan(b)) return a;
  if (std::isnan(a)) return b;
  return std::max(a, b);
}

// The speed (m/s) at which the robot moved towards `point_W` just before `time`: its
// ground-truth displacement over the last `window` s of samples up to `time`, projected on the
// direction from its centre to the point. 0 without two such samples.
double SpeedTowards(const std::vector<PlaybackSample>& samples, double time, Vec2 point_W,
                    double window) {
  const auto after = std::upper_bound(samples.begin(), samples.end(), time,
                                      [](double t, const PlaybackSample& s) { return t < s.time; });
  if (after == samples.begin()) return 0.0;
  const PlaybackSample& now = *(after - 1);
  auto from = std::lower_bound(samples.begin(), after - 1, now.time - window,
                               [](const PlaybackSample& s, double t) { return s.time < t; });
  if (from == after - 1 || now.time <= from->time) return 0.0;
  const Vec2 velocity =
      (now.X_WR.translation() - from->X_WR.translation()) / (now.time - from->time);
  const Vec2 towards = point_W - now.X_WR.translation();
  const double distance = towards.norm();
  return distance > 1e-9 ? velocity.dot(towards) / distance : 0.0;
}

CollisionStats Collisions(const RunTrace& run, const MetricsConfig& config) {
  CollisionStats out;
  std::vector<sim::CollisionEvent> events = run.collisions;
  std::stable_sort(events.begin(), events.end(),
                   [](const auto& a, const auto& b) { return a.time < b.time; });
  std::map<std::pair<int, int>, double> last_contact;  // (kind, pedestrian id) -> time
  for (const sim::CollisionEvent& e : events) {
    const bool pedestrian = e.kind == sim::CollisionKind::kPedestrian;
    const std::pair<int, int> key{pedestrian ? 1 : 0, pedestrian ? e.pedestrian_id : -1};
    const auto it = last_contact.find(key);
    const bool new_incident =
        it == last_contact.end() || !(e.time - it->second < config.collision_merge_time);
    (pedestrian ? out.pedestrian_events : out.static_events) += 1;
    if (new_incident) (pedestrian ? out.pedestrian_incidents : out.static_incidents) += 1;
    if (new_incident && pedestrian &&
        SpeedTowards(run.samples, e.time, e.point_W, config.collision_speed_window) >
            config.collision_driving_speed) {
      ++out.pedestrian_incidents_robot_driving;
    }
    last_contact[key] = e.time;
  }
  for (const PlaybackSample& s : run.samples) {
    out.min_clearance_m = MinSkipNaN(out.min_clearance_m, s.clearance);
    out.min_pedestrian_gap_m = MinSkipNaN(out.min_pedestrian_gap_m, s.pedestrian_gap);
  }
  return out;
}

Repeatability RepeatabilityFromSeries(double path_length, bool path_empty,
                                      const std::vector<int>& run_ids,
                                      const std::vector<RunSeries>& series,
                                      const MetricsConfig& config) {
  Repeatability out;
  out.station_spacing_m = config.station_spacing;
  out.runs = run_ids;
  if (path_empty) return out;
  const double spacing = config.station_spacing;
  const std::size_t stations =
      static_cast<std::size_t>(std::floor(path_length / spacing + 1e-9)) + 1;
  out.station_s_m.resize(stations);
  for (std::size_t k = 0; k < stations; ++k) out.station_s_m[k] = static_cast<double>(k) * spacing;
  out.offsets_m.assign(stations, std::vector<double>(series.size(), kMetricNaN));

  for (std::size_t r = 0; r < series.size(); ++r) {
    const std::vector<double>& s = series[r].progress_m;
    const std::vector<double>& e = series[r].lateral_offset_m;
    for (std::size_t i = 0; i + 1 < s.size(); ++i) {
      const double s0 = s[i], s1 = s[i + 1];
      if (!(s1 > s0) || s1 - s0 > kMaxCrossingStep || !std::isfinite(e[i]) ||
          !std::isfinite(e[i + 1])) {
        continue;
      }
      const double k_lo = std::max(0.0, std::floor(s0 / spacing));
      const double k_hi = std::min(static_cast<double>(stations - 1), std::floor(s1 / spacing) + 1);
      for (double kd = k_lo; kd <= k_hi; kd += 1.0) {
        const std::size_t k = static_cast<std::size_t>(kd);
        const double st = out.station_s_m[k];
        if (st < s0 || st > s1 || !std::isnan(out.offsets_m[k][r])) continue;
        out.offsets_m[k][r] = e[i] + (st - s0) / (s1 - s0) * (e[i + 1] - e[i]);
      }
    }
  }

  out.std_m.assign(stations, kMetricNaN);
  out.spread_m.assign(stations, kMetricNaN);
  double std_sum = 0.0;
  for (std::size_t k = 0; k < stations; ++k) {
    int n = 0;
    double sum = 0.0, lo = kInf, hi = -kInf;
    for (double v : out.offsets_m[k]) {
      if (std::isnan(v)) continue;
      ++n;
      sum += v;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    if (n < 2) continue;
    const double mean = sum / n;
    double ss = 0.0;
    for (double v : out.offsets_m[k]) {
      if (!std::isnan(v)) ss += (v - mean) * (v - mean);
    }
    out.std_m[k] = std::sqrt(ss / (n - 1));
    out.spread_m[k] = hi - lo;
    std_sum += out.std_m[k];
    out.max_spread_m = MaxSkipNaN(out.max_spread_m, out.spread_m[k]);
    ++out.stations_used;
  }
  if (out.stations_used > 0) out.repeatability_m = std_sum / out.stations_used;
  return out;
}

// Each statistic averaged over the summaries with samples; count = their number.
Summary MeanOfSummaries(const std::vector<const Summary*>& summaries) {
  Summary out;
  double mean = 0.0, rms = 0.0, p95 = 0.0, max = 0.0;
  for (const Summary* s : summaries) {
    if (s->count == 0) continue;
    mean += s->mean;
    rms += s->rms;
    p95 += s->p95;
    max += s->max;
    ++out.count;
  }
  if (out.count > 0) {
    out.mean = mean / out.count;
    out.rms = rms / out.count;
    out.p95 = p95 / out.count;
    out.max = max / out.count;
  }
  return out;
}

nlohmann::json Num(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json ToJson(const CollisionStats& c) {
  return {{"static_incidents", c.static_incidents},
          {"pedestrian_incidents", c.pedestrian_incidents},
          {"pedestrian_incidents_robot_driving", c.pedestrian_incidents_robot_driving},
          {"static_events", c.static_events},
          {"pedestrian_events", c.pedestrian_events},
          {"min_clearance_m", Num(c.min_clearance_m)},
          {"min_pedestrian_gap_m", Num(c.min_pedestrian_gap_m)}};
}

nlohmann::json ToJson(const DynamicPointStats& d) {
  return {{"beams_tested", d.beams_tested},     {"beams_rejected", d.beams_rejected},
          {"true_positive", d.true_positive},   {"false_positive", d.false_positive},
          {"false_negative", d.false_negative}, {"rejected_fraction", Num(d.rejected_fraction)},
          {"precision", Num(d.precision)},      {"recall", Num(d.recall)}};
}

nlohmann::json ToJson(const CpuStats& c) {
  return {{"localizer_updates", c.localizer_updates},
          {"localizer_update_mean_ms", Num(c.localizer_update_mean_ms)},
          {"localizer_update_max_ms", Num(c.localizer_update_max_ms)},
          {"sim_time_s", Num(c.sim_time_s)},
          {"cpu_time_s", Num(c.cpu_time_s)},
          {"real_time_factor", Num(c.real_time_factor)}};
}

nlohmann::json PooledAndRunMean(const Summary& pooled, const Summary& run_mean) {
  return {{"pooled", ToJson(pooled)}, {"run_mean", ToJson(run_mean)}};
}

// v rounded to 0.1 mm (dividing by the exact 1e4 keeps 0.1 as the double nearest 0.1).
double RoundTenthMm(double v) { return std::round(v * 1e4) / 1e4; }

}  // namespace

Summary Summarize(const std::vector<double>& values) {
  std::vector<double> v;
  v.reserve(values.size());
  for (double x : values) {
    if (std::isfinite(x)) v.push_back(x);
  }
  Summary out;
  if (v.empty()) return out;
  std::sort(v.begin(), v.end());
  double sum = 0.0, sum2 = 0.0;
  for (double x : v) {
    sum += x;
    sum2 += x * x;
  }
  const double n = static_cast<double>(v.size());
  out.count = static_cast<int>(v.size());
  out.mean = sum / n;
  out.rms = std::sqrt(sum2 / n);
  out.max = v.back();
  const double rank = 0.95 * (n - 1.0);
  const std::size_t lo = static_cast<std::size_t>(std::floor(rank));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  out.p95 = v[lo] + (rank - static_cast<double>(lo)) * (v[hi] - v[lo]);
  return out;
}

RunSeries ComputeRunSeries(const TeachTrace& teach, const RunTrace& run,
                           const MetricsConfig& config) {
  TeachIndex index(teach, config);
  return Series(index, run, config, /*with_localization=*/true);
}

RunMetrics ComputeRunMetrics(const TeachTrace& teach, const RunTrace& run,
                             const MetricsConfig& config) {
  TeachIndex index(teach, config);
  const RunSeries series = Series(index, run, config, /*with_localization=*/true);

  RunMetrics m;
  m.run = run.run;
  m.seed = run.seed;
  m.outcome = run.outcome;
  m.success = run.outcome == Outcome::kSuccess;
  m.samples = static_cast<int>(run.samples.size());
  if (!run.samples.empty()) m.time_s = run.samples.back().time;
  for (std::size_t i = 1; i < run.samples.size(); ++i) {
    m.path_length_m += core::Distance(run.samples[i - 1].X_WR, run.samples[i].X_WR);
  }
  for (double s : series.progress_m) {
    if (std::isfinite(s)) m.progress_m = std::max(m.progress_m, std::min(s, index.path.length()));
  }
  m.tracking_error_m = Summarize(series.tracking_error_m);
  m.localization_error_m = Summarize(series.localization_error_m);
  m.localization_error_rad = Summarize(series.localization_error_rad);
  m.lost_fraction = FractionAbove(series.localization_error_m, config.lost_error);
  m.collisions = Collisions(run, config);

  for (const SwitchRecord& sw : run.switches) {
    SwitchError e;
    e.time_s = sw.time;
    e.from = sw.from;
    e.to = sw.to;
    if (LocalTruth* matcher = index.Matcher(sw.to)) {
      matcher->Reset();
      const PoseError error = Compare(sw.X_MnR, matcher->InMap(sw.X_WR));
      e.error_m = error.distance;
      e.error_rad = error.angle;
      m.switch_error_max_m = MaxSkipNaN(m.switch_error_max_m, e.error_m);
      m.switch_error_max_rad = MaxSkipNaN(m.switch_error_max_rad, e.error_rad);
    }
    m.switches.push_back(e);
  }

  DynamicPointStats& d = m.dynamic_points;
  double cpu_sum_s = 0.0;
  for (const LocalizerSample& u : run.updates) {
    d.beams_tested += u.beams_tested;
    d.beams_rejected += u.beams_rejected;
    d.true_positive += u.true_positive;
    d.false_positive += u.false_positive;
    d.false_negative += u.false_negative;
    cpu_sum_s += u.cpu_s;
    m.cpu.localizer_update_max_ms = MaxSkipNaN(m.cpu.localizer_update_max_ms, 1e3 * u.cpu_s);
  }
  FinishDynamicPoints(d);
  m.cpu.localizer_updates = static_cast<int>(run.updates.size());
  if (!run.updates.empty()) {
    m.cpu.localizer_update_mean_ms = 1e3 * cpu_sum_s / static_cast<double>(run.updates.size());
  }
  m.cpu.sim_time_s = run.sim_time_s;
  m.cpu.cpu_time_s = run.cpu_time_s;
  m.cpu.real_time_factor = run.cpu_time_s > 0.0 ? run.sim_time_s / run.cpu_time_s : kMetricNaN;
  return m;
}

Repeatability ComputeRepeatability(const TeachTrace& teach, const std::vector<RunTrace>& runs,
                                   const MetricsConfig& config) {
  TeachIndex index(teach, config);
  std::vector<RunSeries> series;
  std::vector<int> ids;
  for (const RunTrace& run : runs) {
    series.push_back(Series(index, run, config, /*with_localization=*/false));
    ids.push_back(run.run);
  }
  return RepeatabilityFromSeries(index.path.length(), index.path.empty(), ids, series, config);
}

AggregateMetrics Aggregate(const TeachTrace& teach, const std::vector<RunTrace>& runs,
                           const std::vector<RunMetrics>& metrics, const MetricsConfig& config) {
  RETRACE_CHECK(runs.size() == metrics.size());
  AggregateMetrics a;
  TeachIndex index(teach, config);
  a.runs = static_cast<int>(runs.size());
  a.taught_path_length_m = index.path.length();

  std::vector<RunSeries> series;
  std::vector<int> ids;
  std::vector<double> tracking, loc_m, loc_rad;
  for (const RunTrace& run : runs) {
    series.push_back(Series(index, run, config, /*with_localization=*/true));
    ids.push_back(run.run);
    const RunSeries& s = series.back();
    tracking.insert(tracking.end(), s.tracking_error_m.begin(), s.tracking_error_m.end());
    loc_m.insert(loc_m.end(), s.localization_error_m.begin(), s.localization_error_m.end());
    loc_rad.insert(loc_rad.end(), s.localization_error_rad.begin(), s.localization_error_rad.end());
  }
  a.tracking_error_m_pooled = Summarize(tracking);
  a.localization_error_m_pooled = Summarize(loc_m);
  a.localization_error_rad_pooled = Summarize(loc_rad);
  a.lost_fraction_pooled = FractionAbove(loc_m, config.lost_error);
  a.repeatability =
      RepeatabilityFromSeries(index.path.length(), index.path.empty(), ids, series, config);

  std::vector<const Summary*> tracking_runs, loc_m_runs, loc_rad_runs;
  double time_sum = 0.0, length_sum = 0.0, progress_sum = 0.0, lost_sum = 0.0;
  int lost_runs = 0;
  double switch_sum_m = 0.0, switch_sum_rad = 0.0, update_ms_sum = 0.0;
  for (const RunMetrics& m : metrics) {
    if (m.success) ++a.successes;
    const int outcome = static_cast<int>(m.outcome);
    if (outcome >= 0 && outcome < static_cast<int>(a.outcome_counts.size())) {
      ++a.outcome_counts[static_cast<std::size_t>(outcome)];
    }
    time_sum += m.time_s;
    length_sum += m.path_length_m;
    progress_sum += m.progress_m;
    tracking_runs.push_back(&m.tracking_error_m);
    loc_m_runs.push_back(&m.localization_error_m);
    loc_rad_runs.push_back(&m.localization_error_rad);
    if (std::isfinite(m.lost_fraction)) {
      lost_sum += m.lost_fraction;
      ++lost_runs;
    }

    CollisionStats& c = a.collisions;
    c.static_incidents += m.collisions.static_incidents;
    c.pedestrian_incidents += m.collisions.pedestrian_incidents;
    c.pedestrian_incidents_robot_driving += m.collisions.pedestrian_incidents_robot_driving;
    c.static_events += m.collisions.static_events;
    c.pedestrian_events += m.collisions.pedestrian_events;
    c.min_clearance_m = MinSkipNaN(c.min_clearance_m, m.collisions.min_clearance_m);
    c.min_pedestrian_gap_m = MinSkipNaN(c.min_pedestrian_gap_m, m.collisions.min_pedestrian_gap_m);
    if (m.collisions.static_incidents + m.collisions.pedestrian_incidents > 0) {
      ++a.runs_with_collision;
    }

    for (const SwitchError& e : m.switches) {
      if (!std::isfinite(e.error_m) || !std::isfinite(e.error_rad)) continue;
      ++a.switch_error.count;
      switch_sum_m += e.error_m;
      switch_sum_rad += e.error_rad;
      a.switch_error.max_m = MaxSkipNaN(a.switch_error.max_m, e.error_m);
      a.switch_error.max_rad = MaxSkipNaN(a.switch_error.max_rad, e.error_rad);
    }

    DynamicPointStats& d = a.dynamic_points;
    d.beams_tested += m.dynamic_points.beams_tested;
    d.beams_rejected += m.dynamic_points.beams_rejected;
    d.true_positive += m.dynamic_points.true_positive;
    d.false_positive += m.dynamic_points.false_positive;
    d.false_negative += m.dynamic_points.false_negative;

    a.cpu.localizer_updates += m.cpu.localizer_updates;
    if (m.cpu.localizer_updates > 0) {
      update_ms_sum += m.cpu.localizer_update_mean_ms * m.cpu.localizer_updates;
    }
    a.cpu.localizer_update_max_ms =
        MaxSkipNaN(a.cpu.localizer_update_max_ms, m.cpu.localizer_update_max_ms);
    a.cpu.sim_time_s += m.cpu.sim_time_s;
    a.cpu.cpu_time_s += m.cpu.cpu_time_s;
  }
  if (a.runs > 0) {
    a.success_rate = static_cast<double>(a.successes) / a.runs;
    a.mean_time_s = time_sum / a.runs;
    a.mean_path_length_m = length_sum / a.runs;
    a.mean_progress_m = progress_sum / a.runs;
  }
  a.tracking_error_m_run_mean = MeanOfSummaries(tracking_runs);
  a.localization_error_m_run_mean = MeanOfSummaries(loc_m_runs);
  a.localization_error_rad_run_mean = MeanOfSummaries(loc_rad_runs);
  if (lost_runs > 0) a.lost_fraction_run_mean = lost_sum / lost_runs;
  if (a.switch_error.count > 0) {
    a.switch_error.mean_m = switch_sum_m / a.switch_error.count;
    a.switch_error.mean_rad = switch_sum_rad / a.switch_error.count;
  }
  FinishDynamicPoints(a.dynamic_points);
  if (a.cpu.localizer_updates > 0) {
    a.cpu.localizer_update_mean_ms = update_ms_sum / a.cpu.localizer_updates;
  }
  a.cpu.real_time_factor =
      a.cpu.cpu_time_s > 0.0 ? a.cpu.sim_time_s / a.cpu.cpu_time_s : kMetricNaN;
  return a;
}

nlohmann::json ToJson(const Summary& s) {
  return {{"mean", Num(s.mean)},
          {"rms", Num(s.rms)},
          {"p95", Num(s.p95)},
          {"max", Num(s.max)},
          {"count", s.count}};
}

nlohmann::json ToJson(const RunMetrics& m) {
  nlohmann::json switches = nlohmann::json::array();
  for (const SwitchError& e : m.switches) {
    switches.push_back({{"time_s", Num(e.time_s)},
                        {"from", e.from},
                        {"to", e.to},
                        {"error_m", Num(e.error_m)},
                        {"error_rad", Num(e.error_rad)}});
  }
  return {{"run", m.run},
          {"seed", m.seed},
          {"outcome", std::string(core::EnumName(m.outcome))},
          {"success", m.success},
          {"samples", m.samples},
          {"time_s", Num(m.time_s)},
          {"path_length_m", Num(m.path_length_m)},
          {"progress_m", Num(m.progress_m)},
          {"tracking_error_m", ToJson(m.tracking_error_m)},
          {"localization_error_m", ToJson(m.localization_error_m)},
          {"localization_error_rad", ToJson(m.localization_error_rad)},
          {"lost_fraction", Num(m.lost_fraction)},
          {"collisions", ToJson(m.collisions)},
          {"switch_error",
           {{"count", m.switches.size()},
            {"max_m", Num(m.switch_error_max_m)},
            {"max_rad", Num(m.switch_error_max_rad)},
            {"switches", std::move(switches)}}},
          {"dynamic_points", ToJson(m.dynamic_points)},
          {"cpu", ToJson(m.cpu)}};
}

nlohmann::json ToJson(const AggregateMetrics& a) {
  nlohmann::json outcomes = nlohmann::json::object();
  for (const auto& [outcome, name] : core::EnumTraits<Outcome>::kNames) {
    outcomes[std::string(name)] = a.outcome_counts[static_cast<std::size_t>(outcome)];
  }
  const Repeatability& r = a.repeatability;
  nlohmann::json collisions = ToJson(a.collisions);
  collisions["runs_with_collision"] = a.runs_with_collision;
  return {{"runs", a.runs},
          {"successes", a.successes},
          {"success_rate", Num(a.success_rate)},
          {"outcomes", std::move(outcomes)},
          {"taught_path_length_m", Num(a.taught_path_length_m)},
          {"mean_time_s", Num(a.mean_time_s)},
          {"mean_path_length_m", Num(a.mean_path_length_m)},
          {"mean_progress_m", Num(a.mean_progress_m)},
          {"tracking_error_m",
           PooledAndRunMean(a.tracking_error_m_pooled, a.tracking_error_m_run_mean)},
          {"localization_error_m",
           PooledAndRunMean(a.localization_error_m_pooled, a.localization_error_m_run_mean)},
          {"localization_error_rad",
           PooledAndRunMean(a.localization_error_rad_pooled, a.localization_error_rad_run_mean)},
          {"lost_fraction",
           {{"pooled", Num(a.lost_fraction_pooled)}, {"run_mean", Num(a.lost_fraction_run_mean)}}},
          {"repeatability_m", Num(r.repeatability_m)},
          {"repeatability_max_spread_m", Num(r.max_spread_m)},
          {"repeatability_stations_used", r.stations_used},
          {"collisions", std::move(collisions)},
          {"switch_error",
           {{"count", a.switch_error.count},
            {"mean_m", Num(a.switch_error.mean_m)},
            {"max_m", Num(a.switch_error.max_m)},
            {"mean_rad", Num(a.switch_error.mean_rad)},
            {"max_rad", Num(a.switch_error.max_rad)}}},
          {"dynamic_points", ToJson(a.dynamic_points)},
          {"cpu", ToJson(a.cpu)}};
}

void WriteRepeatabilityCsv(const std::filesystem::path& path, const Repeatability& r) {
  std::vector<std::string> header = {"s_m"};
  for (int run : r.runs) header.push_back("offset_run" + std::to_string(run) + "_m");
  header.push_back("std_m");
  header.push_back("spread_m");
  io::CsvWriter csv(path, header);
  std::vector<io::CsvCell> row;
  for (std::size_t k = 0; k < r.station_s_m.size(); ++k) {
    row.clear();
    row.emplace_back(r.station_s_m[k]);
    for (double v : r.offsets_m[k]) row.emplace_back(RoundTenthMm(v));
    row.emplace_back(RoundTenthMm(r.std_m[k]));
    row.emplace_back(RoundTenthMm(r.spread_m[k]));
    csv.AddRow(row);
  }
  csv.Commit();
}

}  // namespace retrace::bench
