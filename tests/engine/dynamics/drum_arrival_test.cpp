// A winch that winds its weight up to the drum says so when the weight reaches the rope's floor
// there, with the time (World::reportDrumArrivals, docs/servos.md, "Stalls"): the built-in winch
// sat at its floor from 16.9 s with no word while the servo's force climbed for 50 s to its stall.
// The stall's warning still follows; a drum its weight never reaches says nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {
namespace drum_arrival_test {

constexpr double kFloor = 0.01;  // m: the floor a rope's segment keeps open (docs/floors.md)

// The winch's rope from the weight's point (0, 0.1) to its tangent point on the drum (m).
double tangentLength(const World& w, double r) {
  const BodyState &drum = w.body(0), &weight = w.body(1);
  const Vec2 point = weight.position + rotate(Vec2(0, 0.1), weight.angle);
  return std::sqrt(std::max(0.0, (point - drum.position).squaredNorm() - r * r));
}

int countOf(const World& w, const std::string& words) {
  int n = 0;
  for (const std::string& s : w.warnings()) n += s.find(words) != std::string::npos;
  return n;
}

struct Arrival {
  double said = -1;     // the time the warning gives (s)
  double reached = -1;  // the first step's end with the tangent length within its floor (s)
  double stalled = -1;  // the step that said the stall (s)
};

Arrival windUp(const SceneDef& scene, double seconds, double r) {
  World w(scene, "winch");
  Arrival a;
  size_t seen = 0;
  while (w.time() < seconds) {
    w.step(scene.dt, scene.substeps);
    if (a.reached < 0 && tangentLength(w, r) <= kFloor + 1e-5) a.reached = w.time();
    for (; seen < w.warnings().size(); ++seen) {
      const std::string& s = w.warnings()[seen];
      if (s.find("stalled") != std::string::npos && a.stalled < 0) a.stalled = w.time();
      const auto at = s.find("reached the drum 'drum' at t = ");
      if (at != std::string::npos) {
        EXPECT_LT(a.said, 0) << "said twice: " << s;
        a.said = std::stod(s.substr(at + 31));
      }
    }
  }
  return a;
}

TEST(DrumArrival, TheBuiltInWinchSaysWhenItsWeightReachesTheDrumThenStalls) {
  const SceneDef scene = makeScene("winch");
  const Arrival a = windUp(scene, 75, 0.1);
  // r omega = 0.2 m/s from 3.4 m of rope: 16.9 s; said in the step it got there.
  ASSERT_GT(a.reached, 16);
  EXPECT_NEAR(a.said, a.reached, 1e-3);
  EXPECT_LT(a.said, 17.5);
  // The stall still follows, about 50 s later (66.75 s) (max_force / (kp |speed|) = 50 s,
  // docs/servos.md).
  ASSERT_GT(a.stalled, a.said + 45);
  World w(scene, "winch");
  while (w.time() < 75) w.step(scene.dt, scene.substeps);
  ASSERT_EQ(w.warnings().size(), 2u);
  EXPECT_EQ(w.warnings()[0].find("cable 'cable': the weight 'weight' reached the drum 'drum' at "
                                 "t = "),
            0u)
      << w.warnings()[0];
  EXPECT_NE(w.warnings()[0].find("joint 'axle' pushes harder to wind it on until its servo "
                                 "stalls at max_force 10000 N m"),
            std::string::npos)
      << w.warnings()[0];
  EXPECT_EQ(w.warnings()[1].find("joint 'axle': its servo pushes with all it has"), 0u)
      << w.warnings()[1];
}

TEST(DrumArrival, OtherDrumsSpeedsWeightsAndStepsSayItInTheStepTheyArrive) {
  struct Case {
    double r, omega, mass, hz;
    int substeps;
  };
  // Winding either way needs the rope on the other side: a negative omega pays out, so every
  // case winds; radii, speeds, weights and steps vary.
  const Case cases[] = {{0.2, 2, 2, 60, 1},  {0.05, 6, 0.5, 60, 1}, {0.1, 4, 4, 240, 1},
                        {0.15, 1, 1, 30, 4}, {0.1, 8, 1, 120, 2},   {0.3, 3, 8, 60, 4}};
  for (const Case& k : cases) {
    SCOPED_TRACE("r " + std::to_string(k.r) + " omega " + std::to_string(k.omega) + " mass " +
                 std::to_string(k.mass) + " at " + std::to_string(k.hz) + " Hz x " +
                 std::to_string(k.substeps));
    SceneDef scene = makeScene("winch", {{"r", k.r}, {"omega", k.omega}, {"mass", k.mass}});
    scene.dt = 1 / k.hz;
    scene.substeps = k.substeps;
    // About 3.4 m of rope at r omega, then a few seconds more.
    const Arrival a = windUp(scene, 3.6 / (k.r * k.omega) + 3, k.r);
    ASSERT_GT(a.reached, 0);
    EXPECT_NEAR(a.said, a.reached, 1.5 / k.hz);
    if (a.stalled >= 0) {
      EXPECT_GE(a.stalled, a.said);  // the arrival is said first
    }
  }
}

TEST(DrumArrival, ADrumItsWeightNeverReachesSaysNothing) {
  // Lowering (for 20 s: its drum, paid out at 3.1 s, then winds the rope on the other way and
  // its weight reaches it at 25 s, said once though it swings in twice), holding, and a servo too
  // weak to lift the weight.
  for (const auto& set : std::vector<std::vector<std::pair<std::string, double>>>{
           {{"omega", -2.0}}, {{"omega", 0.0}}, {{"mass", 2e4}}}) {
    SceneDef scene = makeScene("winch", set);
    World w(scene, "winch");
    while (w.time() < 20) w.step(scene.dt, scene.substeps);
    EXPECT_EQ(countOf(w, "reached the drum"), 0) << set[0].first << "=" << set[0].second;
    if (set[0].second != -2.0) continue;
    while (w.time() < 30) w.step(scene.dt, scene.substeps);
    EXPECT_EQ(countOf(w, "reached the drum 'drum' at t = 24.9"), 1);
  }
}

}  // namespace drum_arrival_test
}  // namespace cablelab
