// A weight wound up to a sensor drum stops at the rope's floor at the rim and the winch stalls
// (docs/servos.md, "Stalls"; docs/floors.md, "The disc of a round pulley"). The floor along the
// segment closed the tangent length's slack each step while the weight sat at its rim floor, and
// the tangent point moved with the weight: it crept round the drum with the drum's turn (0.006
// m/s at 60 Hz, 4 times that at 240 Hz), up past the drum's centre, and the servo never stalled.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"

namespace cablelab {
namespace winch_rim_floor_test {

struct RimCase {
  double drumMass;
  bool circleDrum;
  double weight, kp, hz, maxForce, speed;
};

constexpr double kR = 0.1;  // m: the drum's radius

SceneDef winchScene(const RimCase& k) {
  using nlohmann::json;
  const json drumShape = k.circleDrum
                             ? json{{"type", "circle"}, {"radius", kR}, {"sensor", true}}
                             : json{{"type", "box"}, {"half_size", {kR, kR}}, {"sensor", true}};
  const double drumInertia = k.drumMass * kR * kR / 2;
  const json scene = {
      {"name", "rim"},
      {"dt", 1 / k.hz},
      {"gravity", {0, -9.81}},
      {"bodies",
       {{{"name", "drum"}, {"position", {0, 0}}, {"mass", k.drumMass}, {"shapes", {drumShape}}},
        {{"name", "weight"},
         {"position", {kR, -0.6}},
         {"mass", k.weight},
         {"shapes", {{{"type", "box"}, {"half_size", {0.04, 0.04}}}}}}}},
      {"joints",
       {{{"type", "revolute"},
         {"name", "winch_axle"},
         {"body_b", "drum"},
         {"anchor", {0, 0}},
         {"servo",
          {{"kp", k.kp},
           {"kd", 2 * std::sqrt(k.kp * (drumInertia + k.weight * kR * kR))},
           {"max_force", k.maxForce},
           {"speed", k.speed}}}}}},
      {"cables",
       {{{"name", "rope"},
         {"start", {{"body", "drum"}, {"radius", kR}, {"side", "left"}, {"turns", 3}}},
         {"end", {{"body", "weight"}}}}}}};
  return sceneFromJson(scene, "rim");
}

// Over the last quarter of 6 s (the weight arrives near 3 s at 2 rad/s): the drum at rest at
// max_force, the weight below the drum's centre, the rope at max_force / r, one stall warning.
void expectStallAtTheRim(const RimCase& k) {
  World w(winchScene(k), "rim");
  const int n = static_cast<int>(std::lround(6 * k.hz));
  double highest = -1, fastestDrum = 0, weakest = k.maxForce, tautest = 0;
  for (int s = 0; s < n; ++s) {
    w.step(1 / k.hz, 1);
    highest = std::max(highest, w.body(1).position.y());
    if (s < 3 * n / 4) continue;
    fastestDrum = std::max(fastestDrum, std::abs(w.body(0).angularVelocity));
    weakest = std::min(weakest, std::abs(w.joint(0).force));
    tautest = std::max(tautest, w.cable(0).tension());
  }
  SCOPED_TRACE("drum " + std::to_string(k.drumMass) + (k.circleDrum ? " circle" : " box") +
               " weight " + std::to_string(k.weight) + " kp " + std::to_string(k.kp) + " at " +
               std::to_string(k.hz) + " Hz, speed " + std::to_string(k.speed));
  // At its floor the weight's centre is sqrt(r^2 + 1 cm^2) from the drum's: it stays 1 cm below
  // the tangent point (it crept up to 9 cm above the centre).
  EXPECT_LT(highest, -0.009);
  EXPECT_LT(fastestDrum, 1e-3);  // rad/s (0.06 to 0.24 rad/s while it crept)
  EXPECT_GT(weakest, 0.99 * k.maxForce);
  EXPECT_LE(tautest, k.maxForce / kR * (1 + 1e-6));
  // The weight's arrival at the drum is said first, then the stall.
  ASSERT_EQ(w.warnings().size(), 2u);
  EXPECT_EQ(w.warnings()[0].find("cable 'rope': the weight 'weight' reached the drum 'drum'"), 0u)
      << w.warnings()[0];
  EXPECT_EQ(w.warnings()[1].find("joint 'winch_axle'"), 0u) << w.warnings()[1];
}

TEST(WinchRimFloor, AWeightWoundUpToASensorDrumStaysBelowItAndTheWinchStalls) {
  // Light and heavy, round and square drums; light and heavy weights; soft and stiff servos;
  // 60 and 240 Hz; a slow and a fast winding. Each lifts its weight (max_force / r > 1.2 m g);
  // none stalled before (the weight crept round the drum).
  const RimCase cases[] = {
      {0.05, true, 0.5, 500, 60, 5, 2},    {0.05, true, 0.5, 500, 240, 5, 2},
      {0.05, false, 0.5, 500, 240, 40, 8}, {1.0, true, 0.5, 500, 240, 5, 8},
      {1.0, false, 2.0, 2e4, 240, 40, 2},  {1.0, false, 0.5, 500, 60, 5, 2},
      {0.05, false, 2.0, 2e4, 60, 40, 2},  {0.05, true, 2.0, 2e4, 60, 40, 2},
  };
  for (const RimCase& k : cases) expectStallAtTheRim(k);
}

}  // namespace winch_rim_floor_test
}  // namespace cablelab
