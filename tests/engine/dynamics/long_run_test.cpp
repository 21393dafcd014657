// Long runs (issue 11): ten simulated minutes of a busy scene with no growth in the rigid cables'
// length error, and the angle precision that needs (Box2D integrates angles in float).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/dynamics/length_targets.h"
#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/busy_scene.h"
#include "tests/support/energy_drift.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

using test::kDt;
constexpr int kMinute = 3600;  // steps

TEST(LongRun, ASpinningBodyKeepsItsAngleToFullPrecisionForTenMinutes) {
  // A free body and one on a frictionless pivot, spinning at 10 rad/s with nothing acting: after
  // 10 min both have turned 6000 rad. Box2D adds each step's turn to a float angle, which past
  // 4096 rad holds it to 0.5 mrad: the bridge keeps Box2D's angle within half a turn.
  SceneDef s;
  s.gravity = Vec2::Zero();
  for (const char* name : {"free", "pivoted"}) {
    BodyDef b;
    b.name = name;
    b.inertia = 0.1;
    b.angularVelocity = 10;
    b.position = Vec2(name[0] == 'f' ? -1 : 1, 0);
    s.bodies.push_back(b);
  }
  JointDef pivot;
  pivot.name = "pivot";
  pivot.bodyB = "pivoted";
  pivot.anchor = Vec2(1, 0);
  s.joints = {pivot};
  World world(s);
  for (int i = 0; i < 10 * kMinute; ++i) world.step(kDt, 1);
  const double turned = 10.0 * 10 * kMinute * kDt;  // 6000 rad
  for (int b = 0; b < 2; ++b) {
    EXPECT_NEAR(world.body(b).angle, turned, 1e-3) << s.bodies[b].name;
    EXPECT_NEAR(world.body(b).angularVelocity, 10, 1e-5);
  }
  EXPECT_NEAR(world.joint(0).value, turned, 1e-3);  // the joint's coordinate does not wrap
}

// The largest length - rest length of each rigid cable, minute by minute (slack is no error).
struct LongRunResult {
  std::vector<std::vector<double>> overLength;  // [minute][cable]
  double highestEnergy = 0, e0 = 0;
  long wrapChanges = 0;
  // The undamped parts' own energy (busy_scene.h): largest |E - E0| over largest kinetic energy.
  double slingDrift = 0, bandDrift = 0;
  std::vector<std::string> warnings;
};

LongRunResult run(const SceneDef& scene, int minutes) {
  World world(scene);
  LongRunResult r;
  r.e0 = r.highestEnergy = world.energy();
  const std::string parts[2] = {"sling.", "band."};
  double partE0[2], worst[2] = {0, 0}, scale[2] = {0, 0}, kinetic = 0;
  for (int p = 0; p < 2; ++p) partE0[p] = test::partEnergy(world, parts[p], kinetic);
  std::vector<std::vector<int>> last(world.cableCount());
  for (int m = 0; m < minutes; ++m) {
    r.overLength.emplace_back(world.cableCount(), 0.0);
    for (int s = 0; s < kMinute; ++s) {
      world.step(kDt, scene.substeps);
      r.highestEnergy = std::max(r.highestEnergy, world.energy());
      for (int p = 0; p < 2; ++p) {
        worst[p] =
            std::max(worst[p], std::abs(test::partEnergy(world, parts[p], kinetic) - partE0[p]));
        scale[p] = std::max(scale[p], kinetic);
      }
      for (int c = 0; c < world.cableCount(); ++c) {
        const Cable& k = world.cable(c);
        if (!k.elastic())
          r.overLength[m][c] = std::max(r.overLength[m][c], k.length() - k.restLength());
        std::vector<int> points;
        for (const WrapPoint& w : k.path()) points.push_back(1000 * w.pulley + w.vertex);
        r.wrapChanges += points != last[c];
        last[c] = points;
      }
    }
  }
  r.slingDrift = worst[0] / std::max(scale[0], 1e-300);
  r.bandDrift = worst[1] / std::max(scale[1], 1e-300);
  r.warnings = world.warnings();
  return r;
}

TEST(LongRun, BusySceneForTenMinutesHasNoGrowthInLengthError) {
  // Rigid cables over a hexagon spinning at 4 rad/s on a pivot (wrap changes all the time), an
  // Atwood machine whose heavier box lands on the ground (contact), the sling, the band and the
  // hand (membranes, servos, the box in its grasp). Before the bridge kept Box2D's angles small
  // the hexagon's cable error doubled each time its angle passed a power of two (5e-6 m in the
  // first minute, 2.3e-5 m in the tenth, 1.2e-4 m after 40 min).
  const SceneDef scene = test::busy(true);
  const LongRunResult r = run(scene, 10);
  int rigid = 0;
  for (size_t c = 0; c < scene.cables.size(); ++c) {
    if (scene.cables[c].stiffness > 0) continue;
    ++rigid;
    const double first = r.overLength.front()[c], final = r.overLength.back()[c];
    // The solve leaves an error below kLengthSlop alone (float rounding) and takes a fifth of any
    // excess off each step, so an error that does not grow stays under the larger of the slop
    // and its first minute's, plus a step's overshoot. (Against the first minute alone, the bound
    // rested on how close the chaotic hexagon came to the slop in its first minute: 3.9e-6 m on
    // one trajectory, 5e-8 m on one that differs from it by rounding, docs/cables.md "Long runs".)
    EXPECT_LE(final, std::max(first, kLengthSlop) + 1e-6) << scene.cables[c].name;
    EXPECT_LT(final, 1e-4) << scene.cables[c].name;
    std::printf("%s: over-length %.2g m in the first minute, %.2g m in the last\n",
                scene.cables[c].name.c_str(), first, final);
  }
  EXPECT_GE(rigid, 2);
  EXPECT_GT(r.wrapChanges, 1000);  // the hexagon and the sling change wraps throughout
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  // The undamped parts keep their energy beside the jointed and touching ones: the midpoint
  // solve is chosen per cable island (docs/cables.md, "Long runs").
  EXPECT_LT(r.slingDrift, 0.02);
  EXPECT_LT(r.bandDrift, 0.02);
  std::printf("10 min busy: sling %.2e band %.2e\n", r.slingDrift, r.bandDrift);
}

TEST(LongRun, UndampedPartsKeepTheirEnergyForTenMinutes) {
  // The sling and the band alone (no joint or contact anywhere: the energy-consistent midpoint
  // solve takes every step). In the busy world they keep it too, their islands taking the
  // midpoint solve beside the others (BusySceneForTenMinutesHasNoGrowthInLengthError).
  World world(test::undampedParts());
  const double e0 = world.energy();
  double worst = 0, scale = 0;
  int midpoint = 0;
  for (int s = 0; s < 10 * kMinute; ++s) {
    world.step(kDt, world.scene().substeps);
    worst = std::max(worst, std::abs(world.energy() - e0));
    scale = std::max(scale, test::kineticEnergy(world));
    midpoint += world.lastStepStats().midpointSolves > 0;
  }
  EXPECT_LT(worst, 0.02 * scale) << worst / scale;
  EXPECT_EQ(midpoint, 10 * kMinute);
}

// Issue 36, item 6: a busy conservative world (tests/data/energy/busy_conservative.json: a square
// spinning in an undamped elastic sling, a point in an undamped band, rigid ropes with weights
// over a hexagon spinning on its pivot, four undamped elastic ropes over another) for ten
// minutes at 60 Hz. Minute by minute, the largest |E - E0| over the largest kinetic energy of
// the world so far stays under 2%, the energy never rises above E0 by more than 1e-3 of that
// scale, and the drift does not speed up: no minute adds more than the first two did, plus
// 0.01% (a drift that grows every minute, 0.9, 0.6, 1.1, ... 6.1%, fails all three). Measured:
// 0.0085% after the first minute, 0.015% after the tenth (0.026% and 0.22%, each minute adding
// 0.02%, while the ropes over the pivoted hexagon pulled along J at the midpoint pose; see
// TheHexagonOnItsPivotKeepsItsEnergyForTenMinutesWithNoGrowth and docs/cables.md, "Long runs").
TEST(LongRun, AConservativeBusySceneKeepsItsEnergyForTenMinutesWithNoGrowth) {
  World world(loadSceneFile(test::dataPath("energy/busy_conservative.json")));
  ASSERT_EQ(world.scene().substeps, 4);
  const double e0 = world.energy();
  double scale = 0, worst = 0, highest = e0;
  std::vector<double> byMinute;
  for (int minute = 0; minute < 10; ++minute) {
    for (int s = 0; s < kMinute; ++s) {
      world.step(kDt, world.scene().substeps);
      const double e = world.energy();
      worst = std::max(worst, std::abs(e - e0));
      highest = std::max(highest, e);
      scale = std::max(scale, test::kineticEnergy(world));
    }
    byMinute.push_back(worst / scale);
    std::printf("minute %d: |E - E0| up to %.3g%% of the scale (%.3g J)\n", minute + 1,
                100 * byMinute.back(), scale);
  }
  EXPECT_LT(byMinute.back(), 0.02);
  EXPECT_LT(highest - e0, 1e-3 * scale);
  const double firstTwo = std::max(byMinute[0], byMinute[1] - byMinute[0]);
  for (size_t m = 1; m < byMinute.size(); ++m)
    EXPECT_LT(byMinute[m] - byMinute[m - 1], firstTwo + 1e-4) << "minute " << m + 1;
  // A weight of the elastic ropes flies into its hexagon, first at 317 s: it bounces off, keeping
  // the energy (hull_bounce.h; issue 36, item 4). Before, a guard dropped the hexagon from its
  // rope (a warning); with Box2D's inelastic knock instead, 3.2% of the scale went.
  for (const std::string& w : world.warnings()) ADD_FAILURE() << w;
}

// The largest |E - E0| over the largest kinetic energy so far, after each of `minutes` minutes of
// `world` at 60 Hz and `substeps`.
std::vector<double> energyDriftByMinute(World& world, int minutes, int substeps) {
  const double e0 = world.energy();
  double worst = 0, scale = 0;
  std::vector<double> byMinute;
  for (int minute = 0; minute < minutes; ++minute) {
    for (int s = 0; s < kMinute; ++s) {
      world.step(kDt, substeps);
      worst = std::max(worst, std::abs(world.energy() - e0));
      scale = std::max(scale, test::kineticEnergy(world));
    }
    byMinute.push_back(worst / scale);
  }
  return byMinute;
}

// Issue 36, item 6: the built-in hexagon (one rigid rope over a hexagon on its pivot, its wrap
// points joining and leaving all the time) for ten minutes at 60 Hz, at its default spin and
// spun at 4 rad/s (as in the busy scene), at 1, 2 and 4 sub-steps, with a light and a heavy
// weight and a light hexagon. The largest |E - E0| stays under 1% of the largest kinetic energy,
// and no minute adds more than the first two did, plus 0.01% of it. Spun at 4 rad/s it lost 0.68%
// a minute at its 2 sub-steps (6.1% after ten minutes) and 1.4% at 1 sub-step: its rope pulled
// along J at the midpoint pose, whose work missed the length change, always the same way after a
// wrap change, and at 1 sub-step a vertex joining fast took the main solve, which gained energy
// (docs/cables.md, "Energy"). Measured now after ten minutes: 0.008% (default), 0.019% (4 rad/s),
// 0.13% (1 sub-step), 0.048% (4), 0.014% (0.3 kg weight), 0.072% (3 kg), 0.13% (0.5 kg hexagon).
TEST(LongRun, TheHexagonOnItsPivotKeepsItsEnergyForTenMinutesWithNoGrowth) {
  struct Case {
    double omega, weight, hexagon;
    int substeps;
  };
  const Case cases[] = {{1.5, 1, 2, 2}, {4, 1, 2, 2}, {4, 1, 2, 1},  {4, 1, 2, 4},
                        {4, 0.3, 2, 2}, {4, 3, 2, 2}, {4, 1, 0.5, 2}};
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << "omega " << c.omega << " weight " << c.weight << " hexagon "
                                    << c.hexagon << " x " << c.substeps);
    World world(makeScene("hexagon",
                          {{"omega", c.omega}, {"m_weight", c.weight}, {"m_hexagon", c.hexagon}}));
    const std::vector<double> byMinute = energyDriftByMinute(world, 10, c.substeps);
    std::printf(
        "hexagon at %g rad/s, %g kg weight, %g kg hexagon, x %d: %.3g%% after 1 min, "
        "%.3g%% after 10\n",
        c.omega, c.weight, c.hexagon, c.substeps, 100 * byMinute[0], 100 * byMinute[9]);
    EXPECT_LT(byMinute.back(), 0.01);
    const double firstTwo = std::max(byMinute[0], byMinute[1] - byMinute[0]);
    for (size_t m = 1; m < byMinute.size(); ++m)
      EXPECT_LT(byMinute[m] - byMinute[m - 1], firstTwo + 1e-4) << "minute " << m + 1;
  }
}

}  // namespace
}  // namespace cablelab
