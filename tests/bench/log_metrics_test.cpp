// The metrics of a log's localization run (bench/replay/log_metrics.hpp).

#include "bench/replay/log_metrics.hpp"

#include <gtest/gtest.h>

#include <string>

namespace retrace::bench {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace log_metrics_test {

LogLocalizeSeries Distances(const std::vector<double>& path_distance_m) {
  LogLocalizeSeries series;
  for (double d : path_distance_m) {
    series.driven_m.push_back(series.driven_m.size());
    series.path_distance_m.push_back(d);
    series.localization_error_m.push_back(d);  // lost where it is far: a table of 40 m errors
    series.localization_error_rad.push_back(0.0);
  }
  return series;
}

// The Intel log localized from its 20th minute in maps taught over its first five: the robot is
// in rooms the teaching drive never went to, 37 to 45 m from the taught route.
TEST(LogMetrics, AWindowThatNeverComesBackOntoTheTaughtRouteIsWarnedAbout) {
  const std::string warning = OffRouteWarning(Distances({44.8, 41.0, 37.24, 39.5, 45.1}));
  EXPECT_NE(warning.find("the localized window never comes within 1.0 m of the taught route (at "
                         "the nearest 37.2 m)"),
            std::string::npos)
      << warning;
  EXPECT_NE(warning.find("errors off the route say little about the method"), std::string::npos);
  // Once back on the route (within 1 m), no warning: the on-route metrics say what they should.
  EXPECT_EQ(OffRouteWarning(Distances({44.8, 12.0, 0.6, 30.0})), "");
  // Without a reference nothing can be told.
  EXPECT_EQ(OffRouteWarning(Distances({kMetricNaN, kMetricNaN})), "");
  EXPECT_EQ(OffRouteWarning(Distances({})), "");
}

}  // namespace log_metrics_test
}  // namespace retrace::bench
