// A bob on a rigid rope dropped from above its anchor falls slack and the rope catches it. With
// restitution e on the bob the catch gives back e^2 of the kinetic energy closing along the rope,
// as a body bounces off its pulley (docs/floors.md, "A rigid rope caught from slack"); e = 0 is
// the plastic catch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "tests/support/energy_drift.h"

namespace cablelab {
namespace {

struct Drop {
  double mass, length, angle, hz;
  int substeps;
};

SceneDef bobAboveItsAnchor(const Drop& d, double restitution) {
  const double x = 0.8 * d.length * std::cos(d.angle), y = 0.8 * d.length * std::sin(d.angle);
  const nlohmann::json scene = {{"name", "drop"},
                                {"dt", 1.0 / d.hz},
                                {"substeps", d.substeps},
                                {"bodies",
                                 {{{"name", "bob"},
                                   {"position", {x, y}},
                                   {"mass", d.mass},
                                   {"velocity", {0.5, 0.0}},
                                   {"shapes",
                                    {{{"type", "circle"},
                                      {"radius", 0.05},
                                      {"sensor", true},
                                      {"restitution", restitution}}}}}}},
                                {"cables",
                                 {{{"name", "rope"},
                                   {"start", {{"body", "bob"}}},
                                   {"end", {{"point", {0.0, 0.0}}}},
                                   {"rest_length", d.length}}}}};
  return sceneFromJson(scene, "drop");
}

// The energy change of the step in which the rope first catches, over the kinetic energy before it.
double firstCatch(const Drop& d, double restitution) {
  World world(bobAboveItsAnchor(d, restitution));
  const Cable& rope = world.cable(0);
  for (int s = 0; s < static_cast<int>(2 * d.hz); ++s) {
    const double before = world.energy(), kinetic = test::kineticEnergy(world);
    world.step(1.0 / d.hz, d.substeps);
    if (rope.tension() > 0) return (world.energy() - before) / kinetic;
  }
  return NAN;
}

const Drop kDrops[] = {{0.3, 0.6, 0.4, 60, 1},  {1.0, 1.2, 0.9, 60, 2},  {3.0, 0.8, 0.6, 30, 1},
                       {0.5, 1.0, 1.1, 240, 4}, {2.0, 0.6, 0.3, 120, 1}, {1.0, 1.5, 0.7, 30, 4},
                       {4.0, 1.0, 0.5, 240, 1}, {0.2, 0.7, 1.0, 120, 2}};

TEST(RopeCatchRestitution, ABobCaughtWithRestitutionOneKeepsItsEnergy) {
  for (const Drop& d : kDrops) {
    const double change = firstCatch(d, 1.0);
    EXPECT_LT(std::abs(change), 0.02) << d.mass << " kg, " << d.length << " m, " << d.hz << " Hz";
  }
}

TEST(RopeCatchRestitution, ABobCaughtWithoutRestitutionStillLosesItsClosingEnergy) {
  for (const Drop& d : kDrops) {
    const double change = firstCatch(d, 0.0);
    EXPECT_LT(change, -0.02) << d.mass << " kg, " << d.length << " m, " << d.hz << " Hz";
  }
}

}  // namespace
}  // namespace cablelab
