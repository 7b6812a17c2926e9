#include "nav/reliability.hpp"

#include <gtest/gtest.h>

#include "tests/support/config_key.hpp"

namespace retrace::nav {
namespace {

BeamEvidence Explained(int explained, int through_wall = 0) {
  BeamEvidence e;
  e.explained = explained;
  e.through_wall = through_wall;
  return e;
}

TEST(Reliability, ScansThatExplainThePoseHoldIt) {
  Reliability r;
  EXPECT_DOUBLE_EQ(r.value(), ReliabilityConfig{}.initial);
  for (int i = 0; i < 100; ++i) r.Update(Explained(90, 2), 0.2);  // 98 % explained, every 0.2 m
  EXPECT_GT(r.value(), 0.95);
  EXPECT_FALSE(r.unreliable());
}

TEST(Reliability, WithoutEvidenceItFallsWithinFiveMetres) {
  // Beams that end short of the walls or in cells the map never saw say nothing: driven on
  // odometry alone, a pose held with certainty falls below the threshold within 5 m.
  Reliability r;
  for (int i = 0; i < 50; ++i) r.Update(Explained(90), 0.2);
  BeamEvidence silent;
  silent.shorter = 60;
  silent.unknown = 49;
  double driven = 0.0;
  while (!r.unreliable() && driven < 20.0) {
    r.Update(silent, 0.2);
    driven += 0.2;
  }
  EXPECT_TRUE(r.unreliable());
  EXPECT_LE(driven, 5.0);
  EXPECT_GT(driven, 2.0);  // not at the first silent scan
}

TEST(Reliability, BeamsThroughMappedWallsMakeItUnreliableAtOnce) {
  Reliability r;
  for (int i = 0; i < 50; ++i) r.Update(Explained(90), 0.2);
  r.Update(Explained(45, 45), 0.2);  // half of the evidence sees through the map
  EXPECT_FALSE(r.unreliable());     // one such scan is not enough
  r.Update(Explained(45, 45), 0.2);
  r.Update(Explained(45, 45), 0.2);
  EXPECT_TRUE(r.unreliable());
  for (int i = 0; i < 50; ++i) r.Update(Explained(90), 0.2);
  r.Update(Explained(30, 50), 0.2);  // most of it does: at once
  EXPECT_TRUE(r.unreliable());
  // The scans support it again: it recovers as fast.
  r.Update(Explained(95, 1), 0.2);
  r.Update(Explained(95, 1), 0.2);
  EXPECT_FALSE(r.unreliable());
}

TEST(Reliability, DisabledNeverUnreliable) {
  ReliabilityConfig c;
  c.enabled = false;
  Reliability r(c);
  for (int i = 0; i < 10; ++i) r.Update(Explained(0, 50), 1.0);
  EXPECT_FALSE(r.unreliable());
}

TEST(Reliability, ConfigErrorsNameTheKey) {
  using retrace::testing::ValidationErrorKey;
  const auto key = [](auto edit) {
    ReliabilityConfig c;
    edit(c);
    return ValidationErrorKey(c);
  };
  EXPECT_EQ(key([](ReliabilityConfig&) {}), retrace::testing::kValid);
  EXPECT_EQ(key([](ReliabilityConfig& c) { c.hold_distance = 0.0; }), "hold_distance");
  EXPECT_EQ(key([](ReliabilityConfig& c) { c.p_wrong = 0.95; }), "p_right");
  EXPECT_EQ(key([](ReliabilityConfig& c) { c.max_beams = 0; }), "max_beams");
  EXPECT_EQ(key([](ReliabilityConfig& c) { c.initial = 1.0; }), "initial");
}

}  // namespace
}  // namespace retrace::nav
