// Issue 36, items 3 and 6: random busy scenes whose bodies knock at their pulleys
// (tests/data/energy/busy_knocks_seed*.json, written by busy_knocks.py there: elastic ropes over
// polygons spinning on their pivots and over point pulleys, Atwood machines over point pulleys
// and circles, free polygons in rope loops, every shape with restitution 1) never gain more than
// 1% of their energy scale in one step, and no minute adds energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "tests/support/energy_drift.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

using test::kDt;
constexpr int kMinute = 3600;  // steps at 60 Hz
constexpr int kMinutes = 3;
// Of the run's largest kinetic energy (the scale): the most one step may gain (issue 36, item 3),
// and the most a minute may end above its start (item 6: no growth; rigid ropes that snap taut
// catch plastically, so the scenes may lose).
constexpr double kStepGain = 0.01;
constexpr double kMinuteGain = 0.005;

struct KnockRun {
  double scale = 0, worstStep = 0;
  std::vector<double> byMinute;  // each minute's energy change (J)
};

KnockRun runMinutes(SceneDef scene, double restitution, int substeps) {
  for (BodyDef& b : scene.bodies)
    for (ShapeDef& s : b.shapes) s.restitution = restitution;
  World world(std::move(scene));
  KnockRun r;
  double e = world.energy();
  for (int minute = 0; minute < kMinutes; ++minute) {
    const double start = e;
    for (int s = 0; s < kMinute; ++s) {
      world.step(kDt, substeps);
      const double next = world.energy();
      r.worstStep = std::max(r.worstStep, next - e);
      e = next;
      r.scale = std::max(r.scale, test::kineticEnergy(world));
    }
    r.byMinute.push_back(e - start);
  }
  return r;
}

// Before (60 Hz, restitution 1): the light side of a rigid Atwood machine thrown at its point
// pulley at 7 m/s passed through it in the bounce's free probe, whose unsettled answer halved the
// step and whose energy bounded the bounce: +126 J in a step, 60% of the scale (seed 13); the
// bob of an elastic rope knocking the polygon spinning on its pivot beside it took the energy the
// polygon gave it, which the polygon then got back as it swung on free of its rope
// (joint_energy.h): 15% (seed 14), 8.0% (16), 6.8% (20), 5.2% (8), 2.8% (18), 2.4% (2); a bob
// wrapped close to its polygon, its rope pulled along the start-of-step J in the main solve, 0.95%
// (seed 20 at 2 sub-steps; docs/knocks.md, "Pulled along the turn"). Measured now: under 0.21%.
// The minutes: -102% to +0.004% (rigid ropes catch plastically).
TEST(BusyKnocks, RandomBusyScenesNeverGainOnePercentInAStepNorAnyEnergyOverAMinute) {
  const char* scenes[] = {"seed13_atwood", "seed2",  "seed8", "seed14",
                          "seed16",        "seed18", "seed20"};
  struct Case {
    double restitution;
    int substeps;
  };
  const Case cases[] = {{1, 1}, {0, 1}, {1, 2}};
  for (const char* name : scenes) {
    const SceneDef scene =
        loadSceneFile(test::dataPath("energy/busy_knocks_" + std::string(name) + ".json"));
    for (const Case& c : cases) {
      SCOPED_TRACE(testing::Message()
                   << name << " restitution " << c.restitution << " x " << c.substeps);
      const KnockRun r = runMinutes(scene, c.restitution, c.substeps);
      std::printf("%s, restitution %g, x %d: worst step %+.3g%%, minutes", name, c.restitution,
                  c.substeps, 100 * r.worstStep / r.scale);
      for (double m : r.byMinute) std::printf(" %+.3g%%", 100 * m / r.scale);
      std::printf(" of %.3g J\n", r.scale);
      EXPECT_LT(r.worstStep, kStepGain * r.scale);
      for (size_t m = 0; m < r.byMinute.size(); ++m)
        EXPECT_LT(r.byMinute[m], kMinuteGain * r.scale) << "minute " << m + 1;
    }
  }
}

}  // namespace
}  // namespace cablelab
