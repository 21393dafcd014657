// Rewind (world_rewind.h): a World rebuilt at step k of a recorded run and played on with the same
// inputs moves exactly as the run did from step k (bit for bit), for scenes with contacts, joints,
// servos, wheels and a drag force.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "engine/dynamics/world.h"
#include "engine/dynamics/world_rewind.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/body_states.h"

namespace cablelab {
namespace world_rewind_test {  // named: unity batches join test files

/// The time-varying inputs of step k: servo targets every step, a force every 5th step, a
/// teleport at step 30 (each recorded in the history between two steps).
void drive(World& w, int k) {
  for (int j = 0; j < w.jointCount(); ++j) w.setServoTarget(j, 0.05 * std::sin(0.1 * k + j));
  const int last = w.bodyCount() - 1;
  if (k % 5 == 0) w.applyForce(last, Vec2(2 * std::cos(0.3 * k), 1), w.body(last).position);
  if (k == 30) w.setBodyVelocity(last, w.body(last).velocity + Vec2(0.1, 0), 0);
  w.step(w.scene().dt, w.scene().substeps);
}

TEST(WorldRewind, PlayingOnFromARestoredStepRepeatsTheRunBitForBit) {
  constexpr int kSteps = 120, kRewindTo = 47;
  for (const char* name : {"hand", "pulley", "hexagon", "capstan", "wheel", "ballast"}) {
    SCOPED_TRACE(name);
    World run(makeScene(name, {}), name);
    std::vector<std::vector<double>> recorded;
    std::vector<double> times;
    for (int k = 0; k < kSteps; ++k) {
      drive(run, k);
      recorded.push_back(test::bodyStates(run));
      times.push_back(run.time());
    }
    auto rewound = rewoundWorld(run.scene(), run.history().inputs(), kRewindTo, name);
    ASSERT_EQ(rewound->stepCount(), kRewindTo);
    EXPECT_EQ(rewound->time(), times[kRewindTo - 1]);
    ASSERT_EQ(test::bodyStates(*rewound), recorded[kRewindTo - 1]);
    // The rewound world has not seen the inputs after its step yet: play on with the same ones.
    for (int k = kRewindTo; k < kSteps; ++k) {
      drive(*rewound, k);
      ASSERT_EQ(test::bodyStates(*rewound), recorded[k]) << "step " << k + 1;
    }
    // Something moved: equal poses are not equal by accident of a world at rest.
    EXPECT_NE(recorded[kRewindTo - 1], recorded.back());
  }
}

TEST(WorldRewind, InputsThroughStepCutsARunOfStepsAndLeavesOutTheNextStepsInputs) {
  WorldHistory h;
  h.add({WorldInput::Kind::Gravity, 0, 1, {0, -9.81}});
  for (int k = 0; k < 5; ++k) h.add({WorldInput::Kind::Step, 1, 1, {0.01}});
  h.add({WorldInput::Kind::ServoTarget, 0, 1, {0.5}});
  h.add({WorldInput::Kind::Step, 1, 1, {0.01}});
  ASSERT_EQ(h.inputs().size(), 4u);  // gravity, 5 steps, servo, 1 step
  const auto three = inputsThroughStep(h.inputs(), 3);
  ASSERT_EQ(three.size(), 2u);
  EXPECT_EQ(three[1].count, 3);
  const auto five = inputsThroughStep(h.inputs(), 5);
  ASSERT_EQ(five.size(), 2u);  // the servo target waits for step 6
  EXPECT_EQ(five[1].count, 5);
  const auto six = inputsThroughStep(h.inputs(), 6);
  ASSERT_EQ(six.size(), 4u);
  EXPECT_EQ(six[2].kind, WorldInput::Kind::ServoTarget);
  EXPECT_THROW(inputsThroughStep(h.inputs(), 7), std::out_of_range);
}

}  // namespace world_rewind_test
}  // namespace cablelab
