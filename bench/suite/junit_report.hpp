#pragma once
// A suite's comparison with its baseline as JUnit XML (`retrace bench --junit`), the test
// report that GitLab, Jenkins, Azure and GitHub's test-report actions read:
//
//   <testsuites name="ci" tests=… failures=… errors="0" skipped="0" time=<wall time, s>>
//     <testsuite name="office.partial" tests=… failures=… … timestamp=<date>>   per entry, mode
//       <properties> retrace_version, git_revision, date, wall_time_s, jobs, suite, suite_file,
//                    suite_digest, baseline_*, set and only (one each) </properties>
//       <testcase classname="office.partial" name="office.partial.success_rate" time="0">
//         <failure type="regression" message="baseline 0.9375, now 0.1875, delta -0.75,
//                  tolerance abs 0.25: worse by 0.75 > 0.25">the same, one item a line</failure>
//       </testcase> …
//
// One testcase per gated row (every verdict but `report`, so the testcases are the metrics
// that can fail the run); a failure for each row that makes `retrace bench` exit 1, so the
// file and the exit code agree: none when there is no baseline or when --update-baseline
// records a new one. Reported-only metrics are left out (the trend file has them).

#include <string>

#include "bench/suite/suite_report.hpp"

namespace retrace::bench {

/// The JUnit XML document (UTF-8, invalid bytes replaced by U+FFFD) of `report`.
std::string JunitXml(const SuiteReport& report, const ReportContext& context);

}  // namespace retrace::bench
