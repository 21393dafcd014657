// A one-sided point pulley the rope does not reach at the start is said once, in plain words
// (docs/scene-format.md, "A pulley the rope does not reach"); it was dropped from the path with no
// word. None of the built-in scenes has one: the membrane's finger, above its band, is on a body
// that falls onto it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/listed_settings.h"

namespace cablelab {
namespace pulley_left_out_test {

using nlohmann::json;

int leftOutWarnings(const World& w) {
  return static_cast<int>(std::count_if(
      w.warnings().begin(), w.warnings().end(),
      [](const std::string& s) { return s.find("is left out") != std::string::npos; }));
}

// A rope from a hanging weight at (-1, -1) up over a point at (0, h) and down to one at (1, -1):
// the route bends round the point's left (over its top), so "side": "left" is right and
// "right" leaves it out. `body` holds the point: "world", or a dynamic or static body at the
// origin.
World overAPoint(const std::string& side, double h, const std::string& bodyType = "") {
  json bodies = {{{"name", "a"}, {"position", {-1, -1}}, {"mass", 1.0}},
                 {{"name", "b"}, {"position", {1, -1}}, {"mass", 1.3}}};
  std::string holder = "world";
  if (!bodyType.empty()) {
    bodies.push_back({{"name", "holder"}, {"type", bodyType}, {"position", {0, 0}}});
    holder = "holder";
  }
  const json scene = {
      {"bodies", bodies},
      {"cables",
       {{{"name", "rope"},
         {"start", {{"body", "a"}}},
         {"end", {{"body", "b"}}},
         {"pulleys",
          {{{"type", "point"}, {"body", holder}, {"point", {0, h}}, {"side", side}}}}}}}};
  return World(sceneFromJson(scene, "test"), "test");
}

TEST(PulleyLeftOut, ASideGivenTheWrongWayRoundIsSaidInPlainWords) {
  for (const double h : {0.5, 2.0, 7.0}) {
    SCOPED_TRACE("point at height " + std::to_string(h));
    World wrong = overAPoint("right", h);
    EXPECT_EQ(wrong.cable(0).wraps(), 0);  // left out: the rope runs straight
    ASSERT_EQ(leftOutWarnings(wrong), 1);
    const std::string& said = wrong.warnings().back();
    EXPECT_NE(said.find("cable 'rope': pulley 0 (a point on 'world') is left out"),
              std::string::npos)
        << said;
    EXPECT_NE(said.find("the rope passes to its left, not its right as \"side\": \"right\" says"),
              std::string::npos)
        << said;
    EXPECT_NE(said.find("(\"side\": \"left\" takes it from the start)"), std::string::npos) << said;
    // The distance named is the point's from the straight rope, 1 + h below it.
    char away[32];
    std::snprintf(away, sizeof away, "(%.3g m away)", 1 + h);
    EXPECT_NE(said.find(away), std::string::npos) << said;
    // The side that bends round it: on the path, nothing said.
    World right = overAPoint("left", h);
    EXPECT_EQ(right.cable(0).wraps(), 1);
    EXPECT_EQ(leftOutWarnings(right), 0);
    // Stepping says it no more than once.
    for (int s = 0; s < 60; ++s) wrong.step(1 / 60.0, 1);
    EXPECT_EQ(leftOutWarnings(wrong), 1);
  }
}

TEST(PulleyLeftOut, ThePointOnTheOtherSideOfTheRopeIsSaidForEitherSide) {
  // A point below the rope between the weights (h = -2, the route a V): "left" is the wrong
  // side there, and the words turn round.
  World wrong = overAPoint("left", -2.0);
  ASSERT_EQ(leftOutWarnings(wrong), 1);
  EXPECT_NE(
      wrong.warnings().back().find("passes to its right, not its left as \"side\": \"left\" says"),
      std::string::npos)
      << wrong.warnings().back();
  EXPECT_EQ(leftOutWarnings(overAPoint("right", -2.0)), 0);
}

TEST(PulleyLeftOut, APointOnAStaticBodyIsSaidOneOnAMovingBodyIsNot) {
  EXPECT_EQ(leftOutWarnings(overAPoint("right", 2.0, "static")), 1);
  EXPECT_EQ(leftOutWarnings(overAPoint("right", 2.0, "kinematic")), 1);  // at rest
  EXPECT_EQ(leftOutWarnings(overAPoint("right", 2.0, "dynamic")), 0);    // may come to the rope
  // A threaded eyelet is on the path whatever the bend.
  World threaded = overAPoint("threaded", 2.0);
  EXPECT_EQ(threaded.cable(0).wraps(), 1);
  EXPECT_EQ(leftOutWarnings(threaded), 0);
}

TEST(PulleyLeftOut, APointBeyondTheRopesEndIsSaidNotToBeReached) {
  // Past the weight's end of the rope: the rope does not pass it at all.
  const json scene = {
      {"bodies", {{{"name", "a"}, {"position", {0, -1}}}}},
      {"cables",
       {{{"name", "rope"},
         {"start", {{"point", {0, 1}}}},
         {"end", {{"body", "a"}}},
         {"pulleys", {{{"type", "point"}, {"point", {0.5, -3}}, {"side", "left"}}}}}}}};
  World w(sceneFromJson(scene, "test"), "test");
  ASSERT_EQ(leftOutWarnings(w), 1);
  EXPECT_NE(w.warnings().back().find("does not reach it (2.06 m away)"), std::string::npos)
      << w.warnings().back();
}

TEST(PulleyLeftOut, NoBuiltInSceneSaysSoAtItsDefaultsOrListedSettings) {
  for (const SceneInfo& info : builtinScenes()) {
    World w(makeScene(info.name));
    EXPECT_EQ(leftOutWarnings(w), 0) << info.name;
    EXPECT_TRUE(w.warnings().empty()) << info.name << ": " << w.warnings().front();
  }
  for (const test::ListedSetting& s : test::listedSettings()) {
    World w(makeScene(s.scene, s.set));
    EXPECT_TRUE(w.warnings().empty()) << test::settingName(s) << ": " << w.warnings().front();
  }
  // The membrane's finger starts above its band, on the side it is not wrapped from, and joins
  // it as it falls: the pulley the earlier load-time check named.
  World membrane(makeScene("membrane"));
  EXPECT_EQ(membrane.cable(0).wraps(), 0);
  for (int s = 0; s < 120 && membrane.cable(0).wraps() == 0; ++s) membrane.step(1 / 60.0, 4);
  EXPECT_EQ(membrane.cable(0).wraps(), 1);
  EXPECT_EQ(leftOutWarnings(membrane), 0);
}

}  // namespace pulley_left_out_test
}  // namespace cablelab
