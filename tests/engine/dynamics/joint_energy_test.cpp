// Jointed bodies keep their energy (joint_energy.h, step_pose.h): Box2D's joint solve took about
// (h omega)^2 / 2 of a swinging link's kinetic energy every step, and a rigid cable over a pulley
// on a swinging arm was held at a pose Box2D's joint correction never reached.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/energy_drift.h"
#include "tests/support/engine_test_support.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace {

// A 3 kg bar, 1 m long, on a pivot at its top end, let go `angle` from hanging; with `chain`, a
// second bar hangs from its lower end by another revolute joint (the first's turn moves the
// second's pivot: a double pendulum, whose links pull on each other as they swing).
SceneDef pendulum(bool chain, double angle = 0.6) {
  SceneDef s;
  s.name = chain ? "double pendulum" : "pendulum";
  BodyDef bar;
  bar.name = "upper";
  bar.mass = 3;
  bar.inertia = 0.25;
  bar.angle = angle;
  bar.position = Vec2(0.5 * std::sin(angle), -0.5 * std::cos(angle));
  bar.shapes = {test::sensorBox(0.03, 0.5)};
  s.bodies = {bar};
  s.joints = {test::worldPivot("upper", Vec2::Zero())};
  if (chain) {
    BodyDef lower = bar;
    lower.name = "lower";
    lower.mass = 1;
    lower.inertia = 1.0 / 12;
    lower.angle = -0.3;
    const Vec2 knee(std::sin(angle), -std::cos(angle));
    lower.position = knee + 0.5 * Vec2(std::sin(-0.3), -std::cos(-0.3));
    s.bodies.push_back(lower);
    JointDef hinge = test::worldPivot("lower", knee);
    hinge.name = "knee";
    hinge.bodyA = "upper";
    s.joints.push_back(hinge);
  }
  return s;
}

// Largest |E - E0| over 60 s at 60 Hz, over the largest kinetic energy.
double drift(World& world, int substeps) {
  const double e0 = world.energy();
  double worst = 0, scale = 0;
  for (int step = 0; step < 3600; ++step) {
    world.step(test::kDt, substeps);
    worst = std::max(worst, std::abs(world.energy() - e0));
    scale = std::max(scale, test::kineticEnergy(world));
  }
  return worst / scale;
}

TEST(JointEnergy, PendulumsOnRevoluteJointsKeepTheirEnergy) {
  // Largest |E - E0| over the largest kinetic energy, measured at 4 sub-steps: 0.79% (single),
  // 0.88% (double); with Box2D's joints alone 27% and 69%, lost for good. At 1 sub-step 3.2%
  // and 3.4%, a swing that comes back (Box2D's semi-implicit Euler), against 61% and 100%.
  for (const bool chain : {false, true}) {
    SCOPED_TRACE(chain ? "double pendulum" : "pendulum");
    World kept(pendulum(chain)), lost(pendulum(chain));
    lost.setJointEnergyKept(false);
    EXPECT_LT(drift(kept, 4), 0.02);
    EXPECT_GT(drift(lost, 4), 0.1);  // the test tells the two apart
  }
}

TEST(JointEnergy, ARigidRopeOverAPulleyOnASwingingArmHoldsItsLength) {
  // The pendulum, let go 0.2 rad out, carries a threaded pulley at its lower end; a rope runs
  // from a fixed point over it to a 0.5 kg weight hanging under the pulley, taut throughout.
  // Measured at 1 sub-step: stretch 0.04 mm (1.3 mm before), energy within 4.1% of the largest
  // kinetic energy (35% lost before); at 4 sub-steps 1.0% (10%).
  SceneDef s = pendulum(false, 0.2);
  BodyDef weight;
  weight.name = "weight";
  weight.mass = 0.5;
  weight.fixedRotation = true;
  weight.position = Vec2(std::sin(0.2), -std::cos(0.2) - 1);
  s.bodies.push_back(weight);
  CableDef rope;
  rope.name = "rope";
  rope.start = {"world", Vec2(-1.5, -1)};
  PulleyDef eyelet;
  eyelet.body = "upper";
  eyelet.point = Vec2(0, -0.5);
  eyelet.side = WrapSide::Threaded;
  rope.pulleys = {eyelet};
  rope.end = {"weight", Vec2::Zero()};
  s.cables = {rope};
  World one(s);
  const double rest = one.cable(0).restLength();
  double stretch = 0;
  for (int step = 0; step < 3600; ++step) {
    one.step(test::kDt, 1);
    stretch = std::max(stretch, one.cable(0).length() - rest);
  }
  EXPECT_LT(stretch, 1e-4);
  World four(s);
  EXPECT_LT(drift(four, 4), 0.02);
}

}  // namespace
}  // namespace cablelab

namespace cablelab {
namespace {

TEST(JointEnergy, AHexagonOnItsPivotKeepsItsEnergyThroughItsWrapChanges) {
  // The built-in hexagon at 1 sub-step (60 Hz) for 60 s: its rope's wrap points come and go
  // 109 times. A step cut short at a wrap event ends on an impulse that takes out what is left
  // of the rope's length rate; read as a tension (309 N on an 11 N rope) it made the next step's
  // geometric stiffness 28 times too large, which damped the weight's swing by 14% of the
  // energy scale in one step (pullingTension, geometric_stiffness.h). That fixed, 3.2% was
  // Box2D's symplectic Euler swing; under the midpoint rule (cable_solver.cpp, stage 5a) 0.46%
  // with the rope pulling along J at the midpoint pose, 0.019% along the discrete gradient of its
  // length (stage 6e; 17.7% before pullingTension; 10.7% before the joints kept their energy).
  World world(makeScene("hexagon"));
  const double share = drift(world, 1);
  std::printf("the hexagon at 1 sub-step: %.2g\n", share);
  EXPECT_LT(share, 1e-3);
}

// A rope from a fixed point over a spinning polygon to a hanging weight.
struct Rope {
  Vec2 start, weight;
  double mass;
  WrapSide side;
};

// A regular polygon (`sides`, the first corner `radius` from its centre at angle `phase`, `mass`)
// spinning at `spin` on a pivot at its centre, with `ropes` over it.
SceneDef ropesOverASpinningPolygon(int sides, double radius, double phase, double mass, double spin,
                                   const std::vector<Rope>& ropes) {
  SceneDef s;
  s.name = "ropes over a spinning polygon";
  BodyDef hub;
  hub.name = "hub";
  hub.mass = mass;
  hub.angularVelocity = spin;
  hub.shapes = {test::sensorPolygon(sides, radius, phase)};
  s.bodies = {hub};
  s.joints = {test::worldPivot("hub", Vec2::Zero())};
  for (size_t i = 0; i < ropes.size(); ++i) {
    BodyDef weight;
    weight.name = "w" + std::to_string(i);
    weight.mass = ropes[i].mass;
    weight.fixedRotation = true;
    weight.position = ropes[i].weight;
    weight.shapes = {test::sensorDisc(0.03)};
    s.bodies.push_back(weight);
    CableDef rope;
    rope.name = "rope" + std::to_string(i);
    rope.start = {"world", ropes[i].start};
    PulleyDef over;
    over.kind = PulleyDef::Kind::Polygon;
    over.body = "hub";
    over.side = ropes[i].side;
    rope.pulleys = {over};
    rope.end = {weight.name, Vec2::Zero()};
    s.cables.push_back(rope);
  }
  return s;
}

TEST(JointEnergy, RopesOverASpinningPolygonOnItsPivotKeepTheirEnergy) {
  // At 1 sub-step, 60 s: their wrap points join and leave as it spins; the rigid ropes take the
  // midpoint rule with the hub's joint (cable_solver.cpp, stage 5a) and pull along the discrete
  // gradient of their lengths (stage 6e). Measured: ten ropes over a hexagon 0.041% (0.11% along
  // J at the midpoint pose, 3.95% under Box2D's integration), one over a square 0.0027% (2.9%,
  // 11.3%).
  std::vector<Rope> ten;
  for (int i = 0; i < 10; ++i)
    ten.push_back({Vec2(-1 + 0.2 * i, 1.5), Vec2(-0.95 + 0.2 * i, -1.5 - 0.1 * i), 0.3 + 0.1 * i,
                   i % 2 == 0 ? WrapSide::Left : WrapSide::Right});
  const std::vector<Rope> one = {{Vec2(-1.2, 0.9), Vec2(0.9, -1.2), 1.0, WrapSide::Left}};
  struct Case {
    SceneDef scene;
    double bound;
  };
  for (const Case& c : {Case{ropesOverASpinningPolygon(6, 0.5, 0, 3, 2, ten), 1e-3},
                        Case{ropesOverASpinningPolygon(4, 0.4, M_PI / 4, 2, 3, one), 1e-3}}) {
    SCOPED_TRACE(std::to_string(c.scene.cables.size()) + " ropes");
    World world(c.scene);
    std::vector<double> rest;
    for (int i = 0; i < world.cableCount(); ++i) rest.push_back(world.cable(i).restLength());
    const double share = drift(world, 1);
    std::printf("%d ropes over a spinning polygon on its pivot: %.2g\n", world.cableCount(), share);
    EXPECT_LT(share, c.bound);
    for (int i = 0; i < world.cableCount(); ++i) EXPECT_LT(world.cable(i).length() - rest[i], 1e-4);
  }
}

}  // namespace
}  // namespace cablelab
