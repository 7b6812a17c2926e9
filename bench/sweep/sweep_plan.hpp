#pragma once
// A sweep checked against its scenario before anything runs: every combination's overrides
// load (strict keys, valid values, a drivable route), each case's seed is known, and the
// sweep has an identity that a results folder records, so that a resumed or merged sweep is
// provably the same sweep.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "bench/sweep/sweep_spec.hpp"
#include "io/config_override.hpp"

namespace retrace::bench {

/// Which cases a process runs: those with case id % count == index - 1 (index 1-based).
struct SweepShard {
  int index = 1;
  int count = 1;

  bool Contains(std::size_t case_id) const {
    return case_id % static_cast<std::size_t>(count) == static_cast<std::size_t>(index - 1);
  }
  /// The number of cases of a sweep of `total` cases in this shard.
  std::size_t CaseCount(std::size_t total) const;
  /// "i/N".
  std::string ToString() const;
};

/// Parses "i/N" with 1 <= i <= N <= 100000. Throws core::ConfigError ("--shard: ...").
SweepShard ParseShard(std::string_view text);

struct SweepPlan {
  SweepSpec spec;
  /// Per combination: the scenario's seed after the combination's overrides; case (c, r)
  /// runs with seed base_seeds[c] + r.
  std::vector<std::uint64_t> base_seeds;
  /// 16 hex digits: a hash of the expanded cases (mode, parameters and values, fixed overrides,
  /// repeats, seeds), the metrics, and the contents of the scenario, world and route files.
  std::string identity;
  /// The scenario's warnings (a switch point too late, ...), each once.
  std::vector<std::string> warnings;

  std::size_t combination(std::size_t case_id) const {
    return case_id / static_cast<std::size_t>(spec.repeats);
  }
  int repeat(std::size_t case_id) const {
    return static_cast<int>(case_id % static_cast<std::size_t>(spec.repeats));
  }
  std::uint64_t seed(std::size_t case_id) const {
    return base_seeds[combination(case_id)] + static_cast<std::uint64_t>(repeat(case_id));
  }
  /// The scenario overrides of a case: its combination's, then `seed` and playback.repeats=1.
  std::vector<io::ConfigOverride> CaseOverrides(std::size_t case_id) const;
};

/// Loads the scenario of every combination (on up to `jobs` threads) and computes the
/// identity. Throws core::ConfigError naming the sweep file, the line of the offending key
/// and the combination; core::IoError / WorldError for files the scenario cannot load.
SweepPlan PlanSweep(SweepSpec spec, int jobs);

}  // namespace retrace::bench
