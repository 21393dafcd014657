// After each Box2D step: bodies on rigid ropes over wheels end the step on the trapezoid rule
// (docs/wheels.md, "Energy of a rope over a wheel").
//
// The midpoint rule (docs/cables.md, "Energy") leaves every path with a circle on it to the main
// solve, whose end velocity Box2D integrates by symplectic Euler, x1 = x0 + h v1: under a steady
// net pull a body runs (h/2) (v1 - v0) a step ahead of its velocity and ends m (a h)^2 / 2 lower
// in energy. Smooth motion gives that back as it slows, but a knock at the rim turns the velocity
// round and keeps the lead: an Atwood machine over a no-slip wheel bouncing at its rim lost 0.8%
// of its energy scale a second. So a group of bodies joined by such ropes and by joints, on which
// nothing else works over the step and which move straight (no knock, no turn), ends at
// x0 + h (v0 + v1) / 2 (exact for a steady pull; the velocities are left as solved). Private to
// engine/dynamics.
#pragma once

#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/model/scene.h"

namespace cablelab {

struct WheelRopeStep {
  std::span<const BodyState> start;                 ///< the bodies at the start of the step
  std::span<const Cable> cables;                    ///< their paths still at the step's start
  const SceneDef* scene = nullptr;                  ///< damping, joints (limits, servos)
  std::span<const std::array<int, 2>> jointBodies;  ///< (body A, body B) per joint, -1: world
  std::span<const char> worked;  ///< per body: something else worked on it (contact, load)
  Vec2 gravity = Vec2::Zero();
  double dt = 0;
};

/// Moves the bodies in `bodies` (the state after the step) of each group that qualifies to the
/// trapezoid rule's end pose and lists them in `changed`.
void keepWheelRopeEnergy(const WheelRopeStep& step, std::vector<BodyState>& bodies,
                         std::vector<int>& changed);

}  // namespace cablelab
