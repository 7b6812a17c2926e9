// route.switch_points: auto — resolved from the route's geometry when the scenario is loaded,
// into the points SuggestSwitchPoints gives; `auto` inside a list is one clear error.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "bench/engine/scenario.hpp"
#include "bench/engine/switch_points.hpp"
#include "bench/engine/switch_visibility.hpp"
#include "core/errors.hpp"
#include "io/config_override.hpp"
#include "nav/scan_constraint.hpp"
#include "tests/support/fake_scan.hpp"
#include "tests/support/source_dir.hpp"

namespace retrace::bench {
namespace {

using retrace::testing::kSource;

Scenario SmallWith(const std::string& override_text) {
  return LoadScenario(kSource / "scenarios/small.yaml", {io::ParseOverride(override_text)});
}

TEST(ScenarioSwitchPoints, AutoIsResolvedFromTheRouteWhenLoaded) {
  const Scenario scenario = SmallWith("route.switch_points=auto");
  EXPECT_TRUE(scenario.switch_points_auto);
  EXPECT_FALSE(scenario.config.route.switch_points.word.has_value());
  // The route's suggestion, each point moved back (within route.switch_window) to where a
  // scan constrains the pose best.
  const std::vector<double> suggested =
      SuggestSwitchPoints(scenario.route, scenario.config.route.revisit_radius);
  const std::vector<double>& chosen = scenario.config.route.switch_points.value;
  ASSERT_FALSE(suggested.empty());  // two laps of the room: the second needs a map of its own
  ASSERT_EQ(chosen.size(), suggested.size());
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    EXPECT_LE(chosen[k], suggested[k]);
    EXPECT_GE(chosen[k], suggested[k] - scenario.config.route.switch_window);
  }
  // The points chosen leave no map revisiting itself, and see enough.
  EXPECT_THAT(scenario.warnings, ::testing::IsEmpty());
}

TEST(ScenarioSwitchPoints, AListIsKeptAsGiven) {
  const Scenario scenario = SmallWith("route.switch_points=[5, 12.5]");
  EXPECT_FALSE(scenario.switch_points_auto);
  EXPECT_EQ(scenario.config.route.switch_points.value, (std::vector<double>{5.0, 12.5}));
}

TEST(ScenarioSwitchPoints, AutoInsideAListIsAnError) {
  try {
    SmallWith("route.switch_points=[auto, 10]");
    FAIL() << "no error";
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("route.switch_points"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("`auto` stands alone"));
  }
}

TEST(ScenarioSwitchPoints, TheDriftBudgetIsOneRouteKeyCheckedByName) {
  const Scenario scenario = SmallWith("route.online_drift_budget=6");
  EXPECT_EQ(scenario.config.route.OnlineSwitching().drift_budget, 6.0);
  EXPECT_DOUBLE_EQ(scenario.config.route.OnlineSwitching().MaxMapLength(), 200.0);
  for (const char* bad : {"route.online_drift_budget=-1", "route.online_drift_budget=0.2"}) {
    try {
      SmallWith(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const core::ConfigError& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr("route.online_drift_budget")) << bad;
    }
  }
  EXPECT_NO_THROW(SmallWith("route.online_drift_budget=0"));  // no budget
}

TEST(ScenarioSwitchPoints, TheRevisitToleranceIsARouteKeyCheckedByName) {
  const Scenario scenario = SmallWith("route.revisit_tolerance=0.3");
  EXPECT_EQ(scenario.config.route.OnlineSwitching().tolerance, 0.3);
  EXPECT_DOUBLE_EQ(scenario.config.route.OnlineSwitching().MinMapLength(), 10.0);
  // Negative, or a loop that would be consistent beyond the drift budget's longest map.
  for (const char* bad : {"route.revisit_tolerance=-0.1", "route.revisit_tolerance=13"}) {
    try {
      SmallWith(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const core::ConfigError& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr("route.revisit_tolerance")) << bad;
    }
  }
}

TEST(ScenarioEvents, ATakeoverDrivesInPlaybackThroughItsPoints) {
  const Scenario scenario =
      SmallWith("events=[{action: takeover, at_route_s: 5, drive: [[5, 1], [8, 4]]}]");
  ASSERT_EQ(scenario.config.events.size(), 1u);
  EXPECT_EQ(scenario.config.events[0].drive.size(), 2u);
  const std::pair<const char*, const char*> bad[] = {
      {"events=[{action: takeover, at_route_s: 5}]", "a takeover needs at least one point"},
      {"events=[{action: takeover, phase: teach, at_route_s: 5, drive: [[5, 1]]}]",
       "a takeover happens in playback only"},
      {"events=[{action: crossing, at_route_s: 5, drive: [[5, 1]], crossing: {from: [2, 2], "
       "to: [5, 5]}}]",
       "only a takeover drives the robot"}};
  for (const auto& [text, want] : bad) {
    try {
      SmallWith(text);
      ADD_FAILURE() << text << " was accepted";
    } catch (const core::ConfigError& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr(want)) << text;
    }
  }
}

TEST(ScenarioSwitchPoints, AScanAlongACorridorConstrainsLittleARoomMuch) {
  using testing::Segment;
  auto constraint = [](const std::vector<Segment>& faces) {
    const core::LaserScan scan = testing::FakeScan(testing::ScanSpec{}, core::Pose2(0.0, 0.0, 0.0),
                                                   [&](const core::Vec2& o, const core::Vec2& d) {
                                                     return testing::NearestSegment(o, d, faces);
                                                   });
    return nav::ScanConstraint(scan, nav::RobotGeometry{});
  };
  const double corridor = constraint({{{-60.0, -1.0}, {60.0, -1.0}}, {{-60.0, 1.0}, {60.0, 1.0}}});
  const double room = constraint({{{-4.0, -3.0}, {6.0, -3.0}},
                                  {{6.0, -3.0}, {6.0, 3.0}},
                                  {{6.0, 3.0}, {-4.0, 3.0}},
                                  {{-4.0, 3.0}, {-4.0, -3.0}}});
  EXPECT_LT(corridor, 1.0);  // nothing fixes the position along the corridor
  EXPECT_GT(room, 30.0);     // two walls across the view fix it
  const std::vector<SwitchPlace> places = {
      {100.0, 5.0, 96.5, 42.0}, {200.0, 50.0, 200.0, 50.0}, {300.0, 3.0, 300.0, 3.0}};
  const std::vector<std::string> w = SwitchPlaceWarnings(places, 30.0);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_THAT(w[0], ::testing::HasSubstr("switch point 1 (100 m) sees little"));
  EXPECT_THAT(w[0], ::testing::HasSubstr("at 96.5 m it would be 42"));
  EXPECT_THAT(w[1], ::testing::HasSubstr("switch point 3 (300 m)"));
  EXPECT_THAT(w[1], ::testing::HasSubstr("no better place"));
}

}  // namespace
}  // namespace retrace::bench
