// The whole `retrace run` command on the small scenario: the files it writes parse back, render
// again and play back again; a figure that cannot be written leaves the results and exit 0.
// (System tier: each runs a teaching drive, a playback and every figure; the sanitizer build
// covers the same code in the episode, results and figure tests.)

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench/engine/playback.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/output/render_results.hpp"
#include "bench/output/results_io.hpp"
#include "bench/run/scenario_run.hpp"
#include "io/json_writer.hpp"
#include "io/tum.hpp"
#include "tests/support/small_run.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
namespace {

using retrace::testing::SmallRunOptions;

// The warnings of a run, kept.
struct WarningList : ProgressSink {
  void Phase(const std::string&, int) override {}
  void AddSimTime(double) override {}
  void UnitDone() override {}
  void Warning(const std::string& text) override { lines.push_back(text); }
  std::vector<std::string> lines;
};

TEST(Episode, RunCommandWritesFilesThatParseBack) {
  const retrace::testing::TempDir tmp;
  const ScenarioRunRequest options = SmallRunOptions("partial", tmp.path() / "small", 1);
  EXPECT_EQ(RunScenario(options, "retrace run (test)", nullptr).exit_code, 0);
  const std::filesystem::path dir = options.out / "partial";
  const nlohmann::json metrics = io::ReadJsonFile(dir / "metrics.json");
  EXPECT_EQ(metrics["mode"], "partial");
  EXPECT_EQ(metrics["runs"].size(), 1u);
  EXPECT_TRUE(metrics["aggregate"].contains("success_rate"));
  EXPECT_TRUE(std::filesystem::exists(dir / "manifest.yaml"));
  const auto gt = io::ReadTum(dir / "runs/0/gt.tum");
  const auto est = io::ReadTum(dir / "runs/0/est.tum");
  EXPECT_EQ(gt.size(), est.size());
  EXPECT_GT(gt.size(), 100u);
  const ModeTeach reread = ReadTeachFolder(dir / "teach", MapMode::kPartial);
  EXPECT_EQ(reread.bundle.maps.size(), 2u);
  EXPECT_EQ(reread.trace.maps.size(), 2u);
  EXPECT_FALSE(std::filesystem::exists(options.out / "partial.tmp"));
  const RunTrace reread_run = ReadRunFolder(dir / "runs/0", 0);
  ASSERT_EQ(reread_run.samples.size(), gt.size());
  EXPECT_EQ(reread_run.samples.back().X_WR, gt.back().pose);
  EXPECT_EQ(reread_run.samples.back().map_index, 1);
  for (const char* figure : {"maps.png", "playback_partial.png", "odometry.png", "errors.png",
                             "snapshot.png", "likelihood.png"}) {
    EXPECT_GT(std::filesystem::file_size(dir / "figures" / figure), 10000u) << figure;
  }
  // `retrace render`: the figures again, from the files alone.
  std::filesystem::remove(dir / "figures/playback_partial.png");
  EXPECT_FALSE(RenderResults(options.out).empty());
  EXPECT_GT(std::filesystem::file_size(dir / "figures/playback_partial.png"), 10000u);

  // Playback again from the written teach folder.
  ScenarioRunRequest again = options;
  again.phases = RunPhases::kPlaybackOnly;
  again.teach_dir = dir / "teach";
  again.out = tmp.path() / "again";
  EXPECT_EQ(RunScenario(again, "retrace playback (test)", nullptr).exit_code, 0);
  EXPECT_TRUE(std::filesystem::exists(again.out / "partial/runs/0/gt.tum"));
}

// Figures come last: when they cannot be written the numbers stay, with a warning and exit 0.
TEST(Episode, AFigureFailureLeavesTheResultsAndTheExitCode) {
  const retrace::testing::TempDir tmp;
  const ScenarioRunRequest options = SmallRunOptions("partial", tmp.path() / "small", 1);
  std::filesystem::create_directories(options.out);
  { std::ofstream(options.out / "figures") << "a file where the figures folder goes\n"; }
  WarningList warnings;
  const int code = RunScenario(options, "retrace run (test)", &warnings).exit_code;
  EXPECT_EQ(code, 0);
  ASSERT_EQ(warnings.lines.size(), 1u);
  EXPECT_EQ(warnings.lines[0].rfind("no figures: ", 0), 0u) << warnings.lines[0];
  EXPECT_TRUE(std::filesystem::exists(options.out / "partial/metrics.json"));
  EXPECT_TRUE(std::filesystem::exists(options.out / "partial/runs/0/gt.tum"));
}

}  // namespace
}  // namespace retrace::bench
