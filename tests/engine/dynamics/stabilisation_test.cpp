// Length stabilisation of rigid cables on steps cut short at a wrap event (docs/cables.md,
// "Events"): a cut step corrects only its share of the per-sub-step length error, so the
// correcting velocity is beta * error / h whatever the cut. Fixing the whole share in a cut of
// 1e-3 h asked for 1000 times that velocity (soak seed 12 threw a finger at 880 m/s).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "engine/dynamics/world.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

using test::kDt;
constexpr double kBaumgarte = 0.2;  // the share of the error fixed per sub-step (cable_solver.cpp)

// A rigid cable from the world origin to a 1 kg load at (L, 0) moving down at 0.5 m/s, a world
// point pulley just under the middle of the cable: the cable sweeps onto it `cut` of the way
// into the step. The cable's rest length is `error` shorter than the cable.
std::unique_ptr<World> makeWorld(double L, double cut, double error) {
  SceneDef s;
  s.name = "stabilisation";
  BodyDef load;
  load.name = "load";
  load.mass = 1;
  load.position = Vec2(L, 0);
  load.velocity = Vec2(0, -0.5);
  load.fixedRotation = true;
  s.bodies = {load};
  CableDef c;
  c.name = "cable";
  c.start = {"world", Vec2::Zero()};
  c.end = {"load", Vec2::Zero()};
  PulleyDef pin;
  // The middle of the cable comes down at 0.25 m/s onto the pin and drapes over it.
  pin.point = Vec2(0.5 * L, -0.25 * cut * kDt);
  pin.side = WrapSide::Left;
  c.pulleys = {pin};
  s.cables = {c};
  s.gravity = Vec2::Zero();
  auto world = std::make_unique<World>(s);
  world->setCableParameters(0, L - error, 0, 0, 0);
  return world;
}

struct StepOutcome {
  double speedChange = 0;  // m/s, of the load over the step
  int events = 0, midpointSolves = 0;
  bool joined = false;
};

StepOutcome stepOnce(double L, double cut, double error) {
  const std::unique_ptr<World> made = makeWorld(L, cut, error);
  World& world = *made;
  const Vec2 v0 = world.body(0).velocity;
  world.step(kDt, 1);
  return {(world.body(0).velocity - v0).norm(), world.lastStepStats().events,
          world.lastStepStats().midpointSolves, world.cable(0).wraps() == 1};
}

// The main solve (a long cable over fixed pulleys) and the midpoint solve (a segment short
// enough for a floor) both: the pulley joins inside the step, and the load is pulled in at about
// beta * error / h, not beta * error / (cut h).
TEST(Stabilisation, ACutStepCorrectsOnlyItsShareOfTheLengthError) {
  for (const double L : {2.0, 0.4}) {
    for (const double cut : {1e-3, 1e-2, 0.3}) {
      const double error = 0.05 * L;
      const StepOutcome o = stepOnce(L, cut, error);
      SCOPED_TRACE("L " + std::to_string(L) + " cut " + std::to_string(cut));
      EXPECT_TRUE(o.joined);
      EXPECT_GE(o.events, 1);  // the step was cut at the join
      // The short cable is the midpoint solve's from the start; the long one the main solve's up
      // to the join (after it, its tension is the cut's impulse over the cut, which reads as a
      // fast swing, and the midpoint solve may take the rest: midpoint_solver.cpp).
      if (L < 0.5) {
        EXPECT_GT(o.midpointSolves, 0);
      }
      // The midpoint rule moves with (v0 + v1) / 2, so its end velocity changes by twice this.
      const double expected = kBaumgarte * error / kDt;
      EXPECT_LT(o.speedChange, 3.0 * expected);
      EXPECT_GT(o.speedChange, 0.5 * expected);  // the error is still corrected
    }
  }
}

}  // namespace
}  // namespace cablelab
