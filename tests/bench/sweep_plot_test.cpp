// RenderSweepPlot reads a sweep's results.csv strictly: a well-formed file (quoted cells, CRLF
// line ends, nan values) becomes sweep.png; a malformed row, a missing column, a cell that is
// not a number or an inconsistent combination is one core::IoError naming the file and line,
// and no PNG is written.

#include "bench/sweep/sweep_plot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "tests/support/temp_dir.hpp"
#include "viz/image.hpp"

namespace retrace::bench {
namespace {

using SweepPlotTest = retrace::testing::TempDirTest;

const std::vector<std::string> kParameters = {"nav.localizer.particles",
                                              "nav.dynamic_rejection.enabled"};
const std::vector<std::string> kMetrics = {"tracking_error_m.pooled.rms", "success_rate"};
const std::string kHeader =
    "case,combo,repeat,seed,nav.localizer.particles,nav.dynamic_rejection.enabled,"
    "tracking_error_m.pooled.rms,success_rate,cpu.real_time_factor\n";

// 3 particle counts x rejection off/on x 3 repeats, as `retrace sweep` writes it.
std::string GridCsv() {
  std::string csv = kHeader;
  int case_id = 0;
  int combo = 0;
  for (int particles : {100, 300, 1000}) {
    for (bool rejection : {false, true}) {
      for (int r = 0; r < 3; ++r) {
        const double tracking = (rejection ? 0.1 : 0.3) + 30.0 / particles + 0.01 * r;
        csv += std::to_string(case_id++) + "," + std::to_string(combo) + "," + std::to_string(r) +
               "," + std::to_string(1000 + r) + "," + std::to_string(particles) + "," +
               (rejection ? "true" : "false") + "," + std::to_string(tracking) + "," +
               (rejection || r > 0 ? "1" : "0.5") + ",42.5\n";
      }
      ++combo;
    }
  }
  return csv;
}

// The message of the IoError that rendering `csv` throws, and that no PNG was written.
std::string ErrorOf(const retrace::testing::TempDir& tmp, const std::string& csv,
                    const std::vector<std::string>& parameters = kParameters,
                    const std::vector<std::string>& metrics = kMetrics) {
  const std::filesystem::path file = tmp.Write("results.csv", csv);
  const std::filesystem::path png = tmp.path() / "sweep.png";
  try {
    RenderSweepPlot(file, parameters, metrics, png, "t");
  } catch (const core::IoError& e) {
    EXPECT_FALSE(std::filesystem::exists(png));
    return e.what();
  }
  ADD_FAILURE() << "no IoError for:\n" << csv;
  return "";
}

TEST_F(SweepPlotTest, RendersAGridSweepFromResultsCsv) {
  const std::filesystem::path csv = tmp_.Write("results.csv", GridCsv());
  const std::filesystem::path png = tmp_.path() / "sweep.png";
  RenderSweepPlot(csv, kParameters, kMetrics, png, "Sweep: particles x rejection");
  const viz::Image img = viz::ReadPng(png);
  EXPECT_EQ(img.width, 1200);  // two columns of panels
  EXPECT_GT(img.height, 700);  // two rows
  const std::string bytes = tmp_.Read(png);
  RenderSweepPlot(csv, kParameters, kMetrics, png, "Sweep: particles x rejection");
  EXPECT_EQ(tmp_.Read(png), bytes);
}

TEST_F(SweepPlotTest, ReadsQuotedCellsCrLfAndNan) {
  std::string csv =
      "case,combo,repeat,seed,map_mode,\"a,b\",tracking_error_m.pooled.rms\r\n"
      "0,0,0,1,partial,\"x, \"\"quoted\"\"\",0.5\r\n"
      "1,0,1,2,partial,\"x, \"\"quoted\"\"\",nan\r\n"
      "\r\n"
      "2,1,0,1,single,\"multi\nline\",-inf\r\n"
      "3,1,1,2,single,\"multi\nline\",NaN\r\n";
  const std::filesystem::path file = tmp_.Write("results.csv", csv);
  const std::filesystem::path png = tmp_.path() / "sweep.png";
  const viz::SweepFigureData data =
      ReadSweepResults(file, {"map_mode", "a,b"}, {"tracking_error_m.pooled.rms"});
  ASSERT_EQ(data.combinations.size(), 2u);
  const viz::SweepCombination& quoted = data.combinations[0];
  EXPECT_EQ(quoted.values, (std::vector<std::string>{"partial", "x, \"quoted\""}));
  ASSERT_EQ(quoted.metrics.size(), 1u);
  ASSERT_EQ(quoted.metrics[0].size(), 2u);  // the blank CRLF line is no case
  EXPECT_EQ(quoted.metrics[0][0], 0.5);
  EXPECT_TRUE(std::isnan(quoted.metrics[0][1]));
  const viz::SweepCombination& multi = data.combinations[1];
  EXPECT_EQ(multi.values, (std::vector<std::string>{"single", "multi\nline"}));
  ASSERT_EQ(multi.metrics[0].size(), 2u);
  EXPECT_EQ(multi.metrics[0][0], -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(multi.metrics[0][1]));
  RenderSweepPlot(file, {"map_mode", "a,b"}, {"tracking_error_m.pooled.rms"}, png, "");
  EXPECT_GT(viz::ReadPng(png).height, 300);
}

TEST_F(SweepPlotTest, AMalformedRowIsAnIoErrorNamingItsLine) {
  std::string csv = GridCsv();
  // Line 4 (the third case) loses its last cell.
  std::size_t pos = 0;
  for (int i = 0; i < 4; ++i) pos = csv.find('\n', pos) + 1;
  csv.erase(csv.rfind(',', pos - 1), pos - 1 - csv.rfind(',', pos - 1));
  const std::string e = ErrorOf(tmp_, csv);
  EXPECT_NE(e.find("results.csv:4: expected 9 cells as in the header, got 8"), std::string::npos)
      << e;
}

TEST_F(SweepPlotTest, AMissingColumnIsAnIoErrorNamingIt) {
  const std::string e =
      ErrorOf(tmp_, GridCsv(), kParameters, {"tracking_error_m.pooled.rms", "repeatability_m"});
  EXPECT_NE(e.find("results.csv:1: no column 'repeatability_m' for the metric"), std::string::npos)
      << e;
  const std::string p = ErrorOf(tmp_, GridCsv(), {"nav.localizer.particle"}, kMetrics);
  EXPECT_NE(p.find("no column 'nav.localizer.particle' for the varied parameter"),
            std::string::npos)
      << p;
}

TEST_F(SweepPlotTest, BadCellsAndInconsistentCasesAreIoErrors) {
  EXPECT_NE(
      ErrorOf(tmp_, kHeader + "0,0,0,1,100,true,fast,1,1\n")
          .find("results.csv:2: tracking_error_m.pooled.rms: expected a number or nan, got 'fast'"),
      std::string::npos);
  EXPECT_NE(
      ErrorOf(tmp_, kHeader + "0,0,0,1,100,true,,1,1\n").find("expected a number or nan, got ''"),
      std::string::npos);
  EXPECT_NE(ErrorOf(tmp_, kHeader + "0,0,0,1,,true,0.5,1,1\n")
                .find("nav.localizer.particles: empty value"),
            std::string::npos);
  EXPECT_NE(ErrorOf(tmp_, kHeader + "0,0,0,1,100,true,0.5,1,1\n1,0,1,1,300,true,0.5,1,1\n")
                .find("results.csv:3: combo '0' has nav.localizer.particles = '300' here but '100' "
                      "at line 2"),
            std::string::npos);
  EXPECT_NE(ErrorOf(tmp_, kHeader + "0,0,0,1,100,true,0.5,1,1\n1,0,0,1,100,true,0.5,1,1\n")
                .find("results.csv:3: combo '0' repeat '0' appears twice (also at line 2)"),
            std::string::npos);
  EXPECT_NE(ErrorOf(tmp_, kHeader + "0,0,0,1,\"100,true,0.5,1,1\n")
                .find("results.csv:2: a quoted cell is not closed"),
            std::string::npos);
  EXPECT_NE(
      ErrorOf(tmp_, kHeader + "0,0,0,1,1\"00,true,0.5,1,1\n").find("a double quote inside a cell"),
      std::string::npos);
  EXPECT_NE(ErrorOf(tmp_, kHeader + "0,0,0,1,\"100\"x,true,0.5,1,1\n")
                .find("text after the closing quote"),
            std::string::npos);
}

TEST_F(SweepPlotTest, AFileThatIsNotASweepsResultsIsAnIoError) {
  EXPECT_NE(ErrorOf(tmp_, "").find("empty file"), std::string::npos);
  EXPECT_NE(ErrorOf(tmp_, kHeader).find("holds a header but no case"), std::string::npos);
  EXPECT_NE(ErrorOf(tmp_, "t,event\n0,goal\n")
                .find("results.csv:1: the header must start with case,combo,repeat,seed"),
            std::string::npos);
  EXPECT_NE(
      ErrorOf(tmp_, "case,combo,repeat,seed,a,a\n0,0,0,1,1,1\n").find("column 'a' appears twice"),
      std::string::npos);
  const std::filesystem::path png = tmp_.path() / "sweep.png";
  EXPECT_THROW(RenderSweepPlot(tmp_.path() / "missing.csv", kParameters, kMetrics, png, ""),
               core::IoError);
  EXPECT_FALSE(std::filesystem::exists(png));
}

}  // namespace
}  // namespace retrace::bench
