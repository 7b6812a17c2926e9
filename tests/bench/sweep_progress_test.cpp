// The text of the sweep's progress line (bench/cli/progress.hpp); the line itself is drawn only on
// a terminal.

#include <gtest/gtest.h>

#include "bench/cli/progress.hpp"

namespace retrace::bench {
namespace {

TEST(SweepProgress, DurationsReadAsSecondsMinutesOrHours) {
  EXPECT_EQ(FormatDuration(0.0), "0 s");
  EXPECT_EQ(FormatDuration(-3.0), "0 s");
  EXPECT_EQ(FormatDuration(42.4), "42 s");
  EXPECT_EQ(FormatDuration(59.6), "1 min 00 s");
  EXPECT_EQ(FormatDuration(200.0), "3 min 20 s");
  EXPECT_EQ(FormatDuration(7500.0), "2 h 05 min");
}

TEST(SweepProgress, BarFillsInProportion) {
  EXPECT_EQ(ProgressBar(0, 8, 8), "[--------]");
  EXPECT_EQ(ProgressBar(3, 8, 8), "[###-----]");
  EXPECT_EQ(ProgressBar(8, 8, 8), "[########]");
  EXPECT_EQ(ProgressBar(9, 8, 4), "[####]");  // never beyond full
  EXPECT_EQ(ProgressBar(0, 0, 4), "[----]");
}

}  // namespace
}  // namespace retrace::bench
