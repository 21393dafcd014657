// The end of a Box2D step for bodies its float arithmetic would leave moving: slow free bodies
// and the midpoint solve's bodies take their end states in double (docs/model.md, "Coupling to
// Box2D"). Called by World::advance after Box2D's step.
#pragma once

#include <span>
#include <utility>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/model/scene.h"

namespace cablelab {

class Box2DBridge;

/// What setEndStates reads of a step: the bodies at its start and their loads.
struct StepEnd {
  std::span<const BodyState> bodies;
  std::span<const BodyDef> defs;
  std::span<const char> excluded;  // jointed or touching at the start
  int dragBody;
  const std::vector<std::pair<int, Vec3>>& ends;  // the midpoint solve's end velocities
  std::span<const Vec3> forces, kicks;
};

/// Sets the end velocities (and the slow bodies' poses) of the step of `dt` Box2D just took.
void setEndStates(Box2DBridge& b2, const StepEnd& s, const Vec2& gravity, double dt);

}  // namespace cablelab
