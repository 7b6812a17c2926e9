#include "bench/metrics/internal/sample_stats.hpp"

#include <algorithm>
#include <cmath>

#include "bench/metrics/metrics.hpp"

namespace retrace::bench {

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

namespace internal {

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

}  // namespace internal
}  // namespace retrace::bench
