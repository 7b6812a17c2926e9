#include "bench/sweep/sweep_spec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

using SweepSpecTest = retrace::testing::TempDirTest;

// The sweep files of these tests name a scenario beside them; LoadSweepSpec does not read it.
const std::string kHead = "scenario: base.yaml\n";

std::vector<std::string> Column(const SweepSpec& spec, const std::string& parameter) {
  std::vector<std::string> out;
  for (std::size_t p = 0; p < spec.parameters.size(); ++p) {
    if (spec.parameters[p] != parameter) continue;
    for (const auto& combination : spec.combinations) out.push_back(combination[p]);
  }
  return out;
}

TEST_F(SweepSpecTest, GridIsTheProductWithTheFirstKeySlowest) {
  const SweepSpec spec = LoadSweepSpec(
      tmp_.Write("grid.yaml", kHead + "repeats: 3\n"
                                      "grid:\n"
                                      "  nav.localizer.particles: [100, 300, 1000]\n"
                                      "  nav.localizer.rejection.enabled: [true, false]\n"));
  EXPECT_EQ(spec.name, "grid");  // the file's stem
  EXPECT_THAT(spec.parameters,
              ElementsAre("nav.localizer.particles", "nav.localizer.rejection.enabled"));
  ASSERT_EQ(spec.combinations.size(), 6u);
  EXPECT_EQ(spec.case_count(), 18u);
  EXPECT_THAT(Column(spec, "nav.localizer.particles"),
              ElementsAre("100", "100", "300", "300", "1000", "1000"));
  EXPECT_THAT(Column(spec, "nav.localizer.rejection.enabled"),
              ElementsAre("true", "false", "true", "false", "true", "false"));
  EXPECT_EQ(spec.mode, MapMode::kPartial);
  EXPECT_EQ(spec.CombinationMode(3), MapMode::kPartial);
  const auto overrides = spec.CombinationOverrides(3);
  ASSERT_EQ(overrides.size(), 2u);
  EXPECT_EQ(overrides[0].key_path, "nav.localizer.particles");
  EXPECT_EQ(overrides[0].value, "300");
  EXPECT_EQ(overrides[1].value, "false");
}

TEST_F(SweepSpecTest, ZipVariesItsListsTogetherInsideTheGrid) {
  const SweepSpec spec = LoadSweepSpec(
      tmp_.Write("zip.yaml", kHead + "grid: {mode: [single, consistent]}\n"
                                     "zip:\n"
                                     "  sim.odometry.alpha1: [1e-4, 2e-4, 4e-4]\n"
                                     "  sim.lidar.mount: [[0, 0, 0], [0.1, 0, 0], [0.2, 0, 0]]\n"));
  ASSERT_EQ(spec.combinations.size(), 6u);
  EXPECT_THAT(Column(spec, "mode"),
              ElementsAre("single", "single", "single", "consistent", "consistent", "consistent"));
  EXPECT_THAT(Column(spec, "sim.odometry.alpha1"),
              ElementsAre("1e-4", "2e-4", "4e-4", "1e-4", "2e-4", "4e-4"));
  // A list value travels as one line of flow YAML, zipped with its partner.
  EXPECT_THAT(Column(spec, "sim.lidar.mount"),
              ElementsAre("[0, 0, 0]", "[0.1, 0, 0]", "[0.2, 0, 0]", "[0, 0, 0]", "[0.1, 0, 0]",
                          "[0.2, 0, 0]"));
  EXPECT_EQ(spec.CombinationMode(0), MapMode::kSingle);
  EXPECT_EQ(spec.CombinationMode(5), MapMode::kConsistent);
  // `mode` picks the map mode; it is no scenario key.
  for (const io::ConfigOverride& o : spec.CombinationOverrides(4)) EXPECT_NE(o.key_path, "mode");
}

TEST_F(SweepSpecTest, LabelsAreRecordedButNotAppliedAndPlotDefaultsToEveryParameter) {
  const SweepSpec labelled = LoadSweepSpec(
      tmp_.Write("l.yaml", kHead + "zip: {drift: [1, 2], sim.odometry.alpha1: [1e-4, 2e-4]}\n"
                                   "labels: [drift]\nplot: [drift]\n"));
  EXPECT_THAT(labelled.labels, ElementsAre("drift"));
  EXPECT_THAT(labelled.plot_parameters, ElementsAre("drift"));
  const auto overrides = labelled.CombinationOverrides(1);
  ASSERT_EQ(overrides.size(), 1u);
  EXPECT_EQ(overrides[0].key_path, "sim.odometry.alpha1");
  const SweepSpec plain =
      LoadSweepSpec(tmp_.Write("p.yaml", kHead + "grid: {a.b: [1], c.d: [2]}\n"));
  EXPECT_THAT(plain.plot_parameters, ElementsAre("a.b", "c.d"));
}

TEST_F(SweepSpecTest, SetIsFlattenedIntoKeyPathsAndCommandLineOverridesFollowIt) {
  const SweepSpec spec = LoadSweepSpec(
      tmp_.Write("set.yaml", kHead + "set:\n"
                                     "  limits: {stall_time: 30, lost_time: 4}\n"
                                     "  route.switch_points: [10, 20]\n"
                                     "  events: [{name: e, at_time: 0, action: pedestrians}]\n"
                                     "grid: {nav.localizer.particles: [100]}\n"),
      {{"seed", "7"}});
  ASSERT_EQ(spec.fixed.size(), 5u);
  EXPECT_EQ(spec.fixed[0].key_path, "limits.stall_time");
  EXPECT_EQ(spec.fixed[1].key_path, "limits.lost_time");
  EXPECT_EQ(spec.fixed[2].value, "[10, 20]");
  EXPECT_EQ(spec.fixed[3].key_path, "events");  // a list replaces the value whole
  EXPECT_EQ(spec.fixed[4].key_path, "seed");
  EXPECT_EQ(spec.fixed_sources[4].section, "--set");
  const auto overrides = spec.CombinationOverrides(0);
  ASSERT_EQ(overrides.size(), 6u);  // the fixed ones first: a varied key has the last word
  EXPECT_EQ(overrides.back().key_path, "nav.localizer.particles");
}

TEST_F(SweepSpecTest, RandomSamplesAreDeterministicInRangeAndFromTheLists) {
  auto write = [&](int seed) {
    return tmp_.Write("random" + std::to_string(seed) + ".yaml",
                      kHead +
                          "random:\n"
                          "  samples: 400\n"
                          "  seed: " +
                          std::to_string(seed) +
                          "\n"
                          "  parameters:\n"
                          "    a.uniform: {uniform: [-0.5, 0.25]}\n"
                          "    a.log: {log_uniform: [1e-3, 1e-1]}\n"
                          "    a.int: {int_uniform: [3, 6]}\n"
                          "    mode: {choice: [partial, consistent]}\n"
                          "    a.choice: {choice: [[1, 2], x]}\n");
  };
  const SweepSpec spec = LoadSweepSpec(write(7));
  ASSERT_EQ(spec.combinations.size(), 400u);
  EXPECT_EQ(LoadSweepSpec(write(7)).combinations, spec.combinations);  // same seed, same draws
  EXPECT_NE(LoadSweepSpec(write(8)).combinations, spec.combinations);

  double uniform_min = 1.0, uniform_max = -1.0, log_below = 0, log_above = 0;
  for (const std::string& v : Column(spec, "a.uniform")) {
    const double x = std::stod(v);
    uniform_min = std::min(uniform_min, x);
    uniform_max = std::max(uniform_max, x);
  }
  EXPECT_GE(uniform_min, -0.5);
  EXPECT_LT(uniform_max, 0.25);
  EXPECT_LT(uniform_min, -0.45);  // 400 draws cover the range
  EXPECT_GT(uniform_max, 0.2);
  for (const std::string& v : Column(spec, "a.log")) {
    const double x = std::stod(v);
    EXPECT_GE(x, 1e-3);
    EXPECT_LT(x, 1e-1);
    (x < 1e-2 ? log_below : log_above) += 1;
  }
  // Log-uniform: as many draws in [1e-3, 1e-2) as in [1e-2, 1e-1); uniform would put 9 % below.
  EXPECT_GT(log_below, 150);
  EXPECT_GT(log_above, 150);
  std::set<std::string> ints, modes, choices;
  for (const std::string& v : Column(spec, "a.int")) {
    EXPECT_EQ(v.find_first_not_of("0123456789"), std::string::npos) << v;  // integral text
    ints.insert(v);
  }
  for (const std::string& v : Column(spec, "mode")) modes.insert(v);
  for (const std::string& v : Column(spec, "a.choice")) choices.insert(v);
  EXPECT_EQ(ints, (std::set<std::string>{"3", "4", "5", "6"}));  // both ends included
  EXPECT_EQ(modes, (std::set<std::string>{"partial", "consistent"}));
  EXPECT_EQ(choices, (std::set<std::string>{"[1, 2]", "x"}));
}

TEST_F(SweepSpecTest, SectionsMultiplyGridOutermost) {
  const SweepSpec spec = LoadSweepSpec(
      tmp_.Write("all.yaml", kHead + "repeats: 2\n"
                                     "grid: {g: [1, 2]}\n"
                                     "zip: {z: [a, b, c]}\n"
                                     "random: {samples: 2, parameters: {r: {uniform: [0, 1]}}}\n"));
  EXPECT_THAT(spec.parameters, ElementsAre("g", "z", "r"));
  ASSERT_EQ(spec.combinations.size(), 12u);
  EXPECT_EQ(spec.case_count(), 24u);
  EXPECT_THAT(Column(spec, "g"),
              ElementsAre("1", "1", "1", "1", "1", "1", "2", "2", "2", "2", "2", "2"));
  EXPECT_THAT(Column(spec, "z"),
              ElementsAre("a", "a", "b", "b", "c", "c", "a", "a", "b", "b", "c", "c"));
  const std::vector<std::string> r = Column(spec, "r");
  EXPECT_NE(r[0], r[1]);
  EXPECT_EQ(r[0], r[2]);  // the same samples inside every grid x zip combination
}

TEST_F(SweepSpecTest, WithoutVariedKeysThereIsOneCombination) {
  const SweepSpec spec =
      LoadSweepSpec(tmp_.Write("plain.yaml", kHead + "repeats: 5\nmode: single\n"));
  EXPECT_EQ(spec.combinations.size(), 1u);
  EXPECT_EQ(spec.case_count(), 5u);
  EXPECT_EQ(spec.CombinationMode(0), MapMode::kSingle);
}

TEST_F(SweepSpecTest, MetricsDefaultAndTimingMetricsAreKeptApart) {
  const SweepSpec plain = LoadSweepSpec(tmp_.Write("d.yaml", kHead));
  EXPECT_EQ(plain.metrics, DefaultSweepMetrics());
  EXPECT_TRUE(plain.timing_metrics.empty());
  const SweepSpec spec = LoadSweepSpec(tmp_.Write(
      "m.yaml", kHead + "metrics: [cpu.real_time_factor, switch_error.max_m, success_rate]\n"));
  EXPECT_THAT(spec.metrics, ElementsAre("switch_error.max_m", "success_rate"));
  EXPECT_THAT(spec.timing_metrics, ElementsAre("cpu.real_time_factor"));
}

TEST_F(SweepSpecTest, KnowsTheAggregateMetrics) {
  const std::vector<std::string>& known = KnownSweepMetrics();
  for (const char* name :
       {"success_rate", "tracking_error_m.pooled.rms", "localization_error_m.pooled.rms",
        "repeatability_m", "switch_error.max_m", "collisions.pedestrian_incidents",
        "cpu.real_time_factor", "dynamic_points.recall"}) {
    EXPECT_NE(std::find(known.begin(), known.end(), name), known.end()) << name;
  }
}

struct BadSpec {
  const char* name;
  std::string yaml;
  const char* message;
};

class SweepSpecBad : public retrace::testing::TempDirTest,
                     public ::testing::WithParamInterface<BadSpec> {};

TEST_P(SweepSpecBad, IsRejectedWithFileLineAndKey) {
  const BadSpec& bad = GetParam();
  const auto file = tmp_.Write("bad.yaml", bad.yaml);
  try {
    LoadSweepSpec(file, {});
    FAIL() << "accepted: " << bad.yaml;
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr(file.string()));
    EXPECT_THAT(e.what(), HasSubstr(bad.message));
  }
}

INSTANTIATE_TEST_SUITE_P(
    SweepFiles, SweepSpecBad,
    ::testing::Values(
        BadSpec{"UnknownTopKey", kHead + "gird: {a: [1]}\n",
                "bad.yaml:2: gird: unknown key; did you mean 'grid'?"},
        BadSpec{"NoScenario", "grid: {a: [1]}\n", "scenario: missing"},
        BadSpec{"EmptyGridList", kHead + "grid:\n  nav.localizer.particles: []\n",
                "bad.yaml:3: grid.nav.localizer.particles: empty list"},
        BadSpec{"EmptyGrid", kHead + "grid: {}\n", "grid: expected a mapping"},
        BadSpec{"GridScalar", kHead + "grid: {a.b: 3}\n", "grid.a.b: expected a list of values"},
        BadSpec{"ZipLengths", kHead + "zip:\n  a.b: [1, 2, 3]\n  c.d: [1, 2]\n",
                "bad.yaml:4: zip.c.d: has 2 values but zip.a.b has 3: zipped lists must have equal "
                "lengths"},
        BadSpec{"UnknownMetric", kHead + "metrics: [success_rate, tracking_rms]\n",
                "metrics[1]: unknown metric 'tracking_rms'; did you mean "
                "'tracking_error_m.pooled.rms'?"},
        BadSpec{"Repeatability", kHead + "metrics: [repeatability_m]\n",
                "'repeatability_m' needs several playback runs of one teaching drive"},
        BadSpec{"MetricTwice", kHead + "metrics: [success_rate, success_rate]\n",
                "'success_rate' is listed twice"},
        BadSpec{"OnlyTimingMetrics", kHead + "metrics: [cpu.real_time_factor]\n",
                "lists only timing metrics"},
        BadSpec{"VariedTwice", kHead + "grid: {a.b: [1]}\nzip: {a.b: [2]}\n",
                "zip.a.b: is already varied in grid (line 2)"},
        BadSpec{"Overlapping", kHead + "grid: {a: [{b: 1}]}\nzip: {a.b: [2]}\n",
                "overlaps with 'a'"},
        BadSpec{"VariedAndFixed", kHead + "set: {a.b: 1}\ngrid: {a.b: [2]}\n",
                "is also fixed by `set` (line 2)"},
        BadSpec{"FixedInsideVaried", kHead + "set: {events.0.count: 1}\ngrid: {events: [[]]}\n",
                "'events.0.count' is also fixed"},
        BadSpec{"PlaybackRepeats", kHead + "grid: {playback.repeats: [1, 2]}\n",
                "replicate with the sweep's `repeats`"},
        BadSpec{"Modes", kHead + "set: {modes: [single]}\n", "set by the sweep itself"},
        BadSpec{"BadMode", kHead + "grid: {mode: [partial, slam]}\n",
                "grid.mode[1]: unknown map mode 'slam'"},
        BadSpec{"BadTopMode", kHead + "mode: slam\n", "unknown map mode 'slam'"},
        BadSpec{"Repeats", kHead + "repeats: 0\n", "repeats: integer 0 out of range"},
        BadSpec{"BadKeyPath", kHead + "grid: {a..b: [1]}\n", "not a key path"},
        BadSpec{"BadName", kHead + "name: a/b\n", "cannot name a results folder"},
        BadSpec{"UnknownDistribution",
                kHead + "random: {samples: 2, parameters: {a: {normal: [0, 1]}}}\n",
                "random.parameters.a.normal: unknown key; did you mean"},
        BadSpec{"EmptyRange", kHead + "random: {samples: 2, parameters: {a: {uniform: [1, 1]}}}\n",
                "needs lo < hi"},
        BadSpec{"LogOfZero",
                kHead + "random: {samples: 2, parameters: {a: {log_uniform: [0, 1]}}}\n",
                "needs 0 < lo < hi"},
        BadSpec{"FractionalInt",
                kHead + "random: {samples: 2, parameters: {a: {int_uniform: [1, 2.5]}}}\n",
                "expected an integer"},
        BadSpec{"NoSamples", kHead + "random: {parameters: {a: {uniform: [0, 1]}}}\n",
                "random.samples: missing"},
        BadSpec{"LabelNotVaried", kHead + "grid: {a.b: [1]}\nlabels: [drift]\n",
                "'drift' is not a varied parameter"},
        BadSpec{"PlotNotVaried", kHead + "grid: {a.b: [1]}\nplot: [c]\n",
                "'c' is not a varied parameter"},
        BadSpec{"TooManyCases",
                kHead + "repeats: 10000\ngrid: {a: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10], b: [1, 2, 3, "
                        "4, 5, 6, 7, 8, 9, 10, 11]}\n",
                "more than 100000 cases"}),
    [](const ::testing::TestParamInfo<BadSpec>& param_info) {
      return std::string(param_info.param.name);
    });

TEST_F(SweepSpecTest, ACommandLineOverrideOfAVariedKeyIsRejected) {
  const auto file = tmp_.Write("s.yaml", kHead + "grid: {nav.localizer.particles: [100, 200]}\n");
  try {
    LoadSweepSpec(file, {{"nav.localizer.particles", "50"}});
    FAIL();
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("is also fixed by --set"));
  }
}

}  // namespace
}  // namespace retrace::bench
