// Every config struct of a file users write names every one of its fields in Reflect(): a
// field left out would be neither read from the file nor written into the manifest, silently.

#include <gtest/gtest.h>

#include "bench/engine/scenario.hpp"
#include "bench/worldgen/campus_generator.hpp"
#include "sim/world_file.hpp"
#include "tests/support/reflect_coverage.hpp"

namespace retrace::bench {
namespace {

TEST(ConfigReflection, EveryFieldOfTheScenarioIsReflected) {
  // ScenarioConfig holds every sim and nav config, the metrics' and the events'.
  EXPECT_EQ(testing::UnreflectedBytes<ScenarioConfig>(), "");
}

TEST(ConfigReflection, EveryFieldOfWorldAndCampusFilesIsReflected) {
  EXPECT_EQ(testing::UnreflectedBytes<sim::WorldConfig>(), "");
  EXPECT_EQ(testing::UnreflectedBytes<CampusConfig>(), "");
}

// The check itself: fields left out of Reflect() are found, in the middle, at the end and
// inside a nested struct in a vector.
struct Inner {
  double a = 0.0;
  int forgotten = 0;
  double b = 0.0;
  template <class V>
  void Reflect(V& v) {
    v("a", a);
    v("b", b);
  }
};
struct ForgetsTheLast {
  double a = 0.0;
  bool flag = false;
  double forgotten = 0.0;
  template <class V>
  void Reflect(V& v) {
    v("a", a);
    v("flag", flag);
  }
};
struct Outer {
  bool on = false;
  std::vector<Inner> inner;
  template <class V>
  void Reflect(V& v) {
    v("on", on);
    v("inner", inner);
  }
};
struct Complete {
  bool on = false;
  double x = 0.0;
  std::optional<double> y;
  template <class V>
  void Reflect(V& v) {
    v("y", y);  // the order of Reflect() does not matter
    v("on", on);
    v("x", x);
  }
};

TEST(ConfigReflection, TheCheckFindsAFieldLeftOut) {
  EXPECT_EQ(testing::UnreflectedBytes<Inner>(),
            "the struct: bytes 8..16 before 'b' hold a field that Reflect() does not name");
  EXPECT_EQ(testing::UnreflectedBytes<ForgetsTheLast>(),
            "the struct: bytes 9..24 at the end hold a field that Reflect() does not name");
  EXPECT_EQ(testing::UnreflectedBytes<Outer>(),
            "inner[]: bytes 8..16 before 'b' hold a field that Reflect() does not name");
  EXPECT_EQ(testing::UnreflectedBytes<Complete>(), "");
}

}  // namespace
}  // namespace retrace::bench
