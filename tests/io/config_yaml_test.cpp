#include "io/config_yaml.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/temp_dir.hpp"

namespace retrace::io {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

enum class Shape { kRound, kSquare };

}  // namespace
}  // namespace retrace::io

template <>
struct retrace::core::EnumTraits<retrace::io::Shape> {
  static constexpr std::array<std::pair<retrace::io::Shape, std::string_view>, 2> kNames{
      {{retrace::io::Shape::kRound, "round"}, {retrace::io::Shape::kSquare, "square"}}};
};

namespace retrace::io {
namespace {

struct Noise {
  double sigma0 = 0.01;
  double sigma1 = 0.001;
  template <class V>
  void Reflect(V& v) {
    v("sigma0", sigma0);
    v("sigma1", sigma1);
  }
  void Validate() const { core::RequireNonNegative("sigma0", sigma0); }
};

struct Sensor {
  int beams = 1081;
  double fov_deg = 270.0;
  bool enabled = true;
  std::string name = "lidar";
  Shape shape = Shape::kRound;
  core::Pose2 mount;
  std::vector<core::Vec2> points;
  std::optional<double> limit;
  Noise noise;
  template <class V>
  void Reflect(V& v) {
    v("beams", beams);
    v("fov_deg", fov_deg);
    v("enabled", enabled);
    v("name", name);
    v("shape", shape);
    v("mount", mount);
    v("points", points);
    v("limit", limit);
    v("noise", noise);
  }
  void Validate() const {
    if (beams < 2) throw core::ConfigError("beams", "needs at least 2 beams");
  }
};

struct Top {
  Sensor lidar;
  std::vector<Noise> extra;
  template <class V>
  void Reflect(V& v) {
    v("lidar", lidar);
    v("extra", extra);
  }
};

class ConfigYamlTest : public ::testing::Test {
 protected:
  // A new file per call, so that one test can load several.
  std::filesystem::path Write(const std::string& text) {
    return tmp_.Write("config_" + std::to_string(counter_++) + ".yaml", text);
  }
  std::string ErrorOf(const std::string& text, const std::vector<std::string>& sets = {}) {
    std::vector<ConfigOverride> overrides;
    for (const auto& s : sets) overrides.push_back(ParseOverride(s));
    const auto file = Write(text);
    try {
      LoadConfigFile<Top>(file, overrides);
    } catch (const core::ConfigError& e) {
      return e.what();
    }
    return "no error";
  }
  retrace::testing::TempDir tmp_;
  int counter_ = 0;
};

TEST_F(ConfigYamlTest, ReadsEveryFieldTypeAndKeepsDefaults) {
  const auto file = Write(
      "lidar:\n"
      "  beams: 541\n"
      "  enabled: false\n"
      "  name: front\n"
      "  shape: square\n"
      "  mount: [0.2, -0.1, 0.5]\n"
      "  points: [[1, 2], [3, 4.5]]\n"
      "  limit: 7\n"
      "  noise: {sigma1: 0.002}\n"
      "extra: [{sigma0: 0.5}, {}]\n");
  const Top top = LoadConfigFile<Top>(file);
  EXPECT_EQ(top.lidar.beams, 541);
  EXPECT_DOUBLE_EQ(top.lidar.fov_deg, 270.0);
  EXPECT_FALSE(top.lidar.enabled);
  EXPECT_EQ(top.lidar.name, "front");
  EXPECT_EQ(top.lidar.shape, Shape::kSquare);
  EXPECT_DOUBLE_EQ(top.lidar.mount.x, 0.2);
  EXPECT_DOUBLE_EQ(top.lidar.mount.theta, 0.5);
  ASSERT_EQ(top.lidar.points.size(), 2u);
  EXPECT_DOUBLE_EQ(top.lidar.points[1].y(), 4.5);
  ASSERT_TRUE(top.lidar.limit.has_value());
  EXPECT_DOUBLE_EQ(*top.lidar.limit, 7.0);
  EXPECT_DOUBLE_EQ(top.lidar.noise.sigma0, 0.01);
  EXPECT_DOUBLE_EQ(top.lidar.noise.sigma1, 0.002);
  ASSERT_EQ(top.extra.size(), 2u);
  EXPECT_DOUBLE_EQ(top.extra[0].sigma0, 0.5);
  EXPECT_DOUBLE_EQ(top.extra[1].sigma0, 0.01);
}

TEST_F(ConfigYamlTest, UnknownKeyNamesFileLineKeyPathAndNearestKey) {
  const std::string msg = ErrorOf("lidar:\n  beams: 10\n  noise:\n    sigma_0: 0.1\n");
  EXPECT_THAT(msg, AllOf(HasSubstr(".yaml:4:"), HasSubstr("lidar.noise.sigma_0"),
                         HasSubstr("unknown key"), HasSubstr("did you mean 'sigma0'")));
}

TEST_F(ConfigYamlTest, UnknownKeyInListElementNamesIndex) {
  EXPECT_THAT(ErrorOf("extra:\n  - {sigma0: 1}\n  - {sigmaa1: 2}\n"),
              AllOf(HasSubstr(":3:"), HasSubstr("extra[1].sigmaa1"), HasSubstr("'sigma1'")));
}

TEST_F(ConfigYamlTest, RejectsNaNInfinityAndWrongTypes) {
  EXPECT_THAT(ErrorOf("lidar: {fov_deg: .nan}\n"),
              AllOf(HasSubstr(":1:"), HasSubstr("lidar.fov_deg"), HasSubstr("finite")));
  EXPECT_THAT(ErrorOf("lidar:\n  fov_deg: -.inf\n"), AllOf(HasSubstr(":2:"), HasSubstr("finite")));
  EXPECT_THAT(ErrorOf("lidar: {beams: 10.5}\n"), HasSubstr("expected an integer"));
  EXPECT_THAT(ErrorOf("lidar: {beams: 99999999999}\n"), HasSubstr("out of range"));
  EXPECT_THAT(ErrorOf("lidar: {enabled: maybe}\n"), HasSubstr("expected true or false"));
  EXPECT_THAT(ErrorOf("lidar: {shape: oval}\n"), HasSubstr("expected one of: round, square"));
  EXPECT_THAT(ErrorOf("lidar: {mount: [1, 2]}\n"), HasSubstr("list of 3 numbers"));
  EXPECT_THAT(ErrorOf("lidar: 5\n"), HasSubstr("expected a mapping"));
  EXPECT_THAT(ErrorOf("extra: {a: 1}\n"), HasSubstr("expected a list"));
}

TEST_F(ConfigYamlTest, ValidateErrorsAreLocatedAtTheOffendingKey) {
  EXPECT_THAT(ErrorOf("lidar:\n  name: x\n  beams: 1\n"),
              AllOf(HasSubstr(":3:"), HasSubstr("lidar.beams"), HasSubstr("at least 2")));
  EXPECT_THAT(ErrorOf("lidar:\n  noise:\n\n    sigma0: -1\n"),
              AllOf(HasSubstr(":4:"), HasSubstr("lidar.noise.sigma0"), HasSubstr(">= 0")));
}

TEST_F(ConfigYamlTest, MalformedYamlNamesTheLine) {
  EXPECT_THAT(ErrorOf("lidar:\n  beams: [1, 2\n  name: x\n"), HasSubstr("invalid YAML"));
}

TEST_F(ConfigYamlTest, MissingFileIsAnIoError) {
  EXPECT_THROW(LoadConfigFile<Top>("/nonexistent/retrace.yaml"), core::IoError);
}

TEST_F(ConfigYamlTest, OverridesSetNestedKeysListElementsAndAreChecked) {
  const auto file = Write("lidar: {beams: 10}\nextra: [{sigma0: 1}, {sigma0: 2}]\n");
  const Top top = LoadConfigFile<Top>(
      file, {ParseOverride("lidar.noise.sigma1=0.5"), ParseOverride("extra.1.sigma0=3"),
             ParseOverride("lidar.points=[[1, 1], [2, 2]]"), ParseOverride("lidar.beams=20")});
  EXPECT_EQ(top.lidar.beams, 20);
  EXPECT_DOUBLE_EQ(top.lidar.noise.sigma1, 0.5);
  EXPECT_DOUBLE_EQ(top.extra[1].sigma0, 3.0);
  EXPECT_EQ(top.lidar.points.size(), 2u);

  EXPECT_THAT(ErrorOf("lidar: {beams: 10}\n", {"lidar.beam=5"}),
              AllOf(HasSubstr("--set lidar.beam=5"), HasSubstr("did you mean 'beams'")));
  EXPECT_THAT(ErrorOf("lidar: {beams: 10}\n", {"lidar.beams=1"}),
              AllOf(HasSubstr("--set lidar.beams=1"), HasSubstr("at least 2")));
  EXPECT_THAT(ErrorOf("extra: [{}]\n", {"extra.3.sigma0=1"}), HasSubstr("out of range"));
  EXPECT_THAT(ErrorOf("lidar: {beams: 10}\n", {"lidar.beams.x=1"}), HasSubstr("--set"));
  EXPECT_THROW(ParseOverride("novalue"), core::ConfigError);
}

TEST_F(ConfigYamlTest, WrittenYamlReadsBackToTheSameValues) {
  Top top;
  top.lidar.beams = 77;
  top.lidar.fov_deg = 0.1;
  top.lidar.shape = Shape::kSquare;
  top.lidar.mount = core::Pose2(1.0 / 3.0, -2.0, 0.25);
  top.lidar.points = {{1.5, 2.5}};
  top.lidar.limit = 3.0;
  top.extra = {Noise{0.3, 0.4}};
  const std::string text = ConfigToYaml(top);
  const Top back = ReadConfig<Top>(YAML::Load(text), "<string>");
  EXPECT_EQ(ConfigToYaml(back), text);
  EXPECT_EQ(back.lidar.mount.x, 1.0 / 3.0);  // shortest round-trip formatting is exact
  EXPECT_THAT(text, HasSubstr("fov_deg: 0.1\n"));
}

}  // namespace
}  // namespace retrace::io
