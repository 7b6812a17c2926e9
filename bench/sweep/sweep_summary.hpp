#pragma once
// The table `retrace sweep` and `retrace merge` print at the end: per combination, the varied
// parameters and the mean of each metric over the repeats.

#include <cstddef>
#include <string>
#include <vector>

#include "bench/sweep/sweep_results.hpp"

namespace retrace::bench {

/// One line per combination (in combo order) of a results table read with `schema`
/// (ResultsSchema of `parameter_count` parameters): combo, the parameter values, and per
/// metric the mean over the combination's rows of its finite values ("-" when none is).
/// At most `max_combinations` lines, then a line saying how many more there are.
std::string SweepSummaryTable(const SweepTableSchema& schema, std::size_t parameter_count,
                              const std::vector<SweepRow>& rows, std::size_t max_combinations = 40);

}  // namespace retrace::bench
